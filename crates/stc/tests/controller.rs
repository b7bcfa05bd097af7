//! The real-time controller against a real process: `stc run --realtime`
//! with a retain file, killed with SIGKILL at random moments and
//! restarted. Every test starts what it needs and stops by itself.

use std::io::{BufRead, BufReader};
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::sync::mpsc;
use std::time::{Duration, Instant};

/// A counter whose RETAIN (and CODESYS PERSISTENT) variables hold an
/// invariant at every cycle end:
/// `b = 2 * a`, `g = a`, `s` holds the digits of `a mod 1000`; `c` is
/// not retained.
const COUNTER: &str = "
VAR_GLOBAL PERSISTENT
    g : DINT;
END_VAR

PROGRAM Main
VAR_EXTERNAL
    g : DINT;
END_VAR
VAR RETAIN
    a : DINT;
    b : LINT;
    s : STRING[8];
END_VAR
VAR
    c : DINT;
END_VAR
VAR_OUTPUT
    oa : DINT;
    ob : LINT;
    og : DINT;
    os : STRING[8];
    oc : DINT;
END_VAR
    a := a + 1;
    b := b + 2;
    g := g + 1;
    s := DINT_TO_STRING(a MOD 1000);
    c := c + 1;
    oa := a; ob := b; og := g; os := s; oc := c;
END_PROGRAM

CONFIGURATION Plant
    RESOURCE Cpu ON PLC
        TASK fast (INTERVAL := T#5ms, PRIORITY := 1);
        PROGRAM Main WITH fast : Main;
    END_RESOURCE
END_CONFIGURATION
";

fn work_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("stc-ctl-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn stc(dir: &Path, args: &[&str]) -> Command {
    let mut c = Command::new(env!("CARGO_BIN_EXE_stc"));
    c.current_dir(dir).args(args);
    c
}

/// One report line: (a, b, g, s, c).
fn values(line: &str) -> Option<(i64, i64, i64, String, i64)> {
    let v: serde_json::Value = serde_json::from_str(line).ok()?;
    let v = v.get("values")?;
    Some((
        v.get("Main.oa")?.as_i64()?,
        v.get("Main.ob")?.as_i64()?,
        v.get("Main.og")?.as_i64()?,
        v.get("Main.os")?.as_str()?.to_string(),
        v.get("Main.oc")?.as_i64()?,
    ))
}

/// The lines of a child's stdout, as they come.
fn lines_of(child: &mut Child) -> mpsc::Receiver<String> {
    let out = child.stdout.take().unwrap();
    let (tx, rx) = mpsc::channel();
    std::thread::spawn(move || {
        for line in BufReader::new(out).lines() {
            let Ok(line) = line else { break };
            if tx.send(line).is_err() {
                break;
            }
        }
    });
    rx
}

struct Rng(u64);

impl Rng {
    fn below(&mut self, n: u64) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0 % n
    }
}

fn check(line: &str) -> i64 {
    let (a, b, g, s, _) = values(line).unwrap_or_else(|| panic!("not a report: {line}"));
    assert_eq!(b, 2 * a, "b is not 2a in {line}");
    assert_eq!(g, a, "g is not a in {line}");
    assert_eq!(s, (a % 1000).to_string(), "s is not a mod 1000 in {line}");
    a
}

#[cfg(unix)]
#[test]
fn sigkill_at_random_moments_never_loses_a_saved_cycle() {
    let dir = work_dir("kill");
    std::fs::write(dir.join("counter.st"), COUNTER).unwrap();
    let seed = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .unwrap()
        .as_nanos() as u64
        | 1;
    eprintln!("seed {seed}");
    let mut rng = Rng(seed);
    let deadline = Instant::now() + Duration::from_secs(120);
    let args = [
        "run",
        "counter.st",
        "--realtime",
        "--retain",
        "state.ret",
        "--trace",
        "--format",
        "json",
    ];
    // The last cycle a run printed: it was saved before it was printed.
    let mut last_printed = 0i64;
    let mut kills = 0;
    for round in 0..20 {
        assert!(Instant::now() < deadline, "took too long ({round} rounds)");
        let mut child = stc(&dir, &args)
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap();
        let rx = lines_of(&mut child);
        // Wait for the first report (the program has started), then let it
        // run a random while, reading as it goes.
        let first = rx
            .recv_timeout(Duration::from_secs(30))
            .expect("no report within 30 s");
        let a = check(&first);
        assert!(
            a > last_printed,
            "round {round}: restarted at a = {a}, but a = {last_printed} was saved"
        );
        let (_, _, _, _, c) = values(&first).unwrap();
        assert_eq!(c, 1, "c is not retained: {first}");
        last_printed = a;
        let run_for = Duration::from_millis(rng.below(120));
        let until = Instant::now() + run_for;
        while let Ok(line) = rx.recv_timeout(until.saturating_duration_since(Instant::now())) {
            last_printed = check(&line);
        }
        // SIGKILL: no handler runs, the process stops wherever it is.
        child.kill().unwrap();
        child.wait().unwrap();
        kills += 1;
        for line in rx.try_iter() {
            last_printed = check(&line);
        }
        let mut err = String::new();
        std::io::Read::read_to_string(child.stderr.as_mut().unwrap(), &mut err).unwrap();
        // Overruns may be reported on a loaded machine; a refused or
        // unwritable retain file may not.
        assert!(
            !err.contains("not loaded") && !err.contains("cannot"),
            "round {round}: {err}"
        );
    }
    assert_eq!(kills, 20);
    // A last clean run with --cold starts from the initial values.
    let out = stc(&dir, &args)
        .args(["--cold", "--cycles", "1"])
        .output()
        .unwrap();
    let text = String::from_utf8_lossy(&out.stdout);
    assert_eq!(check(text.lines().next().unwrap()), 1, "{text}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_corrupted_or_foreign_retain_file_is_reported_and_ignored() {
    let dir = work_dir("bad");
    std::fs::write(dir.join("counter.st"), COUNTER).unwrap();
    let run = |extra: &[&str]| {
        let out = stc(
            &dir,
            &["run", "counter.st", "--realtime", "--retain", "state.ret"],
        )
        .args(["--format", "json", "--cycles", "3"])
        .args(extra)
        .output()
        .unwrap();
        assert!(out.status.success(), "{out:?}");
        let text = String::from_utf8(out.stdout).unwrap();
        (
            check(text.lines().last().unwrap()),
            String::from_utf8(out.stderr).unwrap(),
        )
    };
    // No file: a cold start; the next run continues where it stopped.
    assert_eq!(run(&[]).0, 3);
    let (a, err) = run(&[]);
    assert_eq!(a, 6);
    assert!(err.contains("warm start"), "{err}");
    // A flipped byte: reported, not loaded.
    let path = dir.join("state.ret");
    let mut bytes = std::fs::read(&path).unwrap();
    let n = bytes.len();
    bytes[n / 2] ^= 0x10;
    std::fs::write(&path, &bytes).unwrap();
    let (a, err) = run(&[]);
    assert_eq!(a, 3);
    assert!(
        err.contains("checksum") && err.contains("not loaded"),
        "{err}"
    );
    // Another program's file.
    let other = COUNTER
        .replace("    a := a + 1;", "    a := a + 1;\n    z := z + 1;")
        .replace(
            "VAR RETAIN\n    a : DINT;",
            "VAR RETAIN\n    z : INT;\n    a : DINT;",
        );
    std::fs::write(dir.join("other.st"), other).unwrap();
    let out = stc(
        &dir,
        &["run", "other.st", "--realtime", "--retain", "state.ret"],
    )
    .args(["--cycles", "1"])
    .output()
    .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("another program"), "{err}");
    // --cold ignores a valid file.
    assert_eq!(run(&["--cold"]).0, 3);
    let _ = std::fs::remove_dir_all(&dir);
}

/// A program on the Modbus server: coil 0 (`%QX0.0`) and holding
/// register 0 (`%QW0`) are written by the client; the program answers on
/// coil 1, and on input registers the allocation map binds.
const PLANT: &str = "
PROGRAM Main
VAR
    start    AT %QX0.0 : BOOL;
    lamp     AT %QX0.1 : BOOL;
    setpoint AT %QW0 : INT;
    level : INT;
    count : DINT;
END_VAR
    count := count + 1;
    lamp := start;
    level := setpoint * 2;
END_PROGRAM
";

const PLANT_MAP: &str = "
# input registers for two unlocated variables
[[modbus]]
variable = \"Main.level\"
table = \"input\"
address = 0

[[modbus]]
variable = \"Main.count\"
table = \"input\"
address = 10
";

/// Starts the plant with a Modbus server on a free loopback port.
fn start_plant(dir: &Path) -> (Child, SocketAddr) {
    std::fs::write(dir.join("plant.st"), PLANT).unwrap();
    std::fs::write(dir.join("plant.toml"), PLANT_MAP).unwrap();
    let mut child = stc(
        dir,
        &[
            "run",
            "plant.st",
            "--realtime",
            "--tick",
            "10ms",
            "--io-map",
            "plant.toml",
            "--modbus",
            "127.0.0.1:0",
            "--format",
            "json",
        ],
    )
    .stdout(Stdio::null())
    .stderr(Stdio::piped())
    .spawn()
    .unwrap();
    let err = child.stderr.take().unwrap();
    let (tx, rx) = mpsc::channel();
    std::thread::spawn(move || {
        for line in BufReader::new(err).lines() {
            let Ok(line) = line else { break };
            if let Some(a) = line.strip_prefix("note: modbus: listening on ") {
                let _ = tx.send(a.parse::<SocketAddr>().unwrap());
            }
        }
    });
    let addr = rx
        .recv_timeout(Duration::from_secs(30))
        .expect("the server did not start within 30 s");
    (child, addr)
}

/// Polls until `f` holds, for at most 10 s.
fn eventually(what: &str, mut f: impl FnMut() -> bool) {
    let end = Instant::now() + Duration::from_secs(10);
    while Instant::now() < end {
        if f() {
            return;
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    panic!("{what}: not within 10 s");
}

use std::net::SocketAddr;
use tokio_modbus::client::sync::{self, Reader, Writer};
use tokio_modbus::ExceptionCode;

#[test]
fn a_modbus_client_reads_and_writes_a_running_program() {
    let dir = work_dir("modbus");
    let (mut child, addr) = start_plant(&dir);
    let mut c = sync::tcp::connect_with_timeout(addr, Some(Duration::from_secs(5))).unwrap();
    // The cycle counter moves (input registers 10-11, high word first).
    let count = |c: &mut sync::Context| {
        let r = c.read_input_registers(10, 2).unwrap().unwrap();
        (u32::from(r[0]) << 16) | u32::from(r[1])
    };
    let first = count(&mut c);
    eventually("the cycle counter moves", || count(&mut c) > first);
    // A coil written by the client: the program sees it in a next cycle.
    assert_eq!(c.read_coils(0, 2).unwrap().unwrap(), [false, false]);
    c.write_single_coil(0, true).unwrap().unwrap();
    eventually("lamp follows start", || {
        c.read_coils(1, 1).unwrap().unwrap() == [true]
    });
    // A holding register: level = 2 * setpoint on input register 0.
    c.write_multiple_registers(0, &[21]).unwrap().unwrap();
    eventually("level = 2 * setpoint", || {
        c.read_input_registers(0, 1).unwrap().unwrap() == [42]
    });
    assert_eq!(c.read_holding_registers(0, 1).unwrap().unwrap(), [21]);
    // Exceptions: an address outside the tables, a function not served.
    assert_eq!(
        c.read_holding_registers(5000, 1).unwrap(),
        Err(ExceptionCode::IllegalDataAddress)
    );
    assert_eq!(
        c.write_single_coil(9, true).unwrap(),
        Err(ExceptionCode::IllegalDataAddress)
    );
    assert_eq!(
        c.read_input_registers(0, 200).unwrap(),
        Err(ExceptionCode::IllegalDataValue)
    );
    // A malformed frame (a length field far past any frame) and a
    // half-sent one cost only their own connection.
    use std::io::Write;
    let mut bad = std::net::TcpStream::connect(addr).unwrap();
    bad.write_all(&[0, 1, 0, 0, 0xff, 0xff, 1, 3, 0, 0])
        .unwrap();
    let mut half = std::net::TcpStream::connect(addr).unwrap();
    half.write_all(&[0, 2, 0, 0]).unwrap();
    let before = count(&mut c);
    eventually("the server still answers", || count(&mut c) > before);
    let mut c2 = sync::tcp::connect_with_timeout(addr, Some(Duration::from_secs(5))).unwrap();
    assert_eq!(c2.read_coils(0, 2).unwrap().unwrap(), [true, true]);
    drop((bad, half));
    child.kill().unwrap();
    child.wait().unwrap();
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn io_map_mistakes_are_exit_2_with_their_line_before_anything_runs() {
    let dir = work_dir("map");
    std::fs::write(dir.join("plant.st"), PLANT).unwrap();
    let cases = [
        (
            "[[modbus]]\nvariable = \"Main.nope\"\ntable = \"input\"\naddress = 0\n",
            "bad.toml:2: ",
        ),
        (
            "[[modbus]]\nvariable = \"Main.level\"\ntable = \"coil\"\naddress = 7\n",
            "bad.toml:2: `Main.level` is INT: a coil holds a BOOL",
        ),
        (
            "[[modbus]]\nvariable = \"Main.level\"\ntable = \"holding\"\naddress = 0\n",
            "bad.toml:4: holding register 0 is used twice",
        ),
        (
            "[[modbus]]\nvariable = \"Main.level\"\ntable = \"input\"\naddress = 0\nperiod = 3\n",
            "bad.toml:5: ",
        ),
    ];
    for (text, expected) in cases {
        std::fs::write(dir.join("bad.toml"), text).unwrap();
        let out = stc(
            &dir,
            &[
                "run",
                "plant.st",
                "--realtime",
                "--io-map",
                "bad.toml",
                "--cycles",
                "1",
            ],
        )
        .output()
        .unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{text}: {err}");
        assert!(
            err.starts_with(&format!("error: {expected}")),
            "{text}: {err}"
        );
        assert!(out.stdout.is_empty(), "{text}: something ran");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn the_tank_example_runs_with_its_allocation_map() {
    let examples = Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples"));
    let out = stc(
        examples,
        &[
            "run",
            "tank_control.st",
            "--realtime",
            "--tick",
            "10ms",
            "--io-map",
            "tank_control.toml",
            "--modbus",
            "127.0.0.1:0",
            "--cycles",
            "3",
        ],
    )
    .output()
    .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{err}");
    assert!(
        err.contains("note: modbus: listening on 127.0.0.1:"),
        "{err}"
    );
}

#[test]
fn fifty_concurrent_clients_are_served_while_the_cycles_go_on() {
    let dir = work_dir("clients");
    let (mut child, addr) = start_plant(&dir);
    let deadline = Instant::now() + Duration::from_secs(60);
    let clients: Vec<_> = (0..50u16)
        .map(|i| {
            std::thread::spawn(move || {
                let mut c =
                    sync::tcp::connect_with_timeout(addr, Some(Duration::from_secs(20))).unwrap();
                let mut last = 0u32;
                for _ in 0..20 {
                    let r = c.read_input_registers(10, 2).unwrap().unwrap();
                    let n = (u32::from(r[0]) << 16) | u32::from(r[1]);
                    assert!(n >= last, "client {i}: the counter went back");
                    last = n;
                    // Past the holding registers: an exception, and the
                    // connection goes on.
                    assert_eq!(
                        c.write_single_register(100 + i, i).unwrap(),
                        Err(ExceptionCode::IllegalDataAddress)
                    );
                }
                last
            })
        })
        .collect();
    let mut seen = Vec::new();
    for c in clients {
        seen.push(c.join().expect("a client failed"));
    }
    assert!(Instant::now() < deadline, "50 clients took more than 60 s");
    // The program kept cycling while they were served (all 50 may be
    // served within one cycle: the counter then moves just after).
    let mut c = sync::tcp::connect_with_timeout(addr, Some(Duration::from_secs(5))).unwrap();
    let min = *seen.iter().min().unwrap();
    eventually("the counter moves on", || {
        let r = c.read_input_registers(10, 2).unwrap().unwrap();
        ((u32::from(r[0]) << 16) | u32::from(r[1])) > min
    });
    child.kill().unwrap();
    child.wait().unwrap();
    let _ = std::fs::remove_dir_all(&dir);
}

/// The Python `pymodbus` client (installed with pip when missing) against
/// a running program: tests/modbus/pymodbus_client.py.
#[test]
fn the_pymodbus_client_drives_a_running_program() {
    let has = |py: &str| {
        Command::new(py)
            .args(["-c", "import pymodbus"])
            .output()
            .is_ok_and(|o| o.status.success())
    };
    if !has("python3") {
        let pip = Command::new("python3")
            .args(["-m", "pip", "install", "--quiet", "pymodbus"])
            .output()
            .expect("python3 is needed for this test");
        assert!(
            pip.status.success(),
            "pip install pymodbus: {}",
            String::from_utf8_lossy(&pip.stderr)
        );
    }
    let dir = work_dir("pymodbus");
    let (mut child, addr) = start_plant(&dir);
    let script = Path::new(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../tests/modbus/pymodbus_client.py"
    ));
    let out = Command::new("python3")
        .arg(script)
        .args([addr.ip().to_string(), addr.port().to_string()])
        .output()
        .unwrap();
    child.kill().unwrap();
    child.wait().unwrap();
    assert!(
        out.status.success(),
        "{}{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// SIGTERM ends a controller after its current cycle, with a last save
/// even between two interval saves; the next start continues from it.
#[cfg(unix)]
#[test]
fn sigterm_stops_after_the_cycle_and_saves_the_retained_variables() {
    let dir = work_dir("term");
    std::fs::write(dir.join("counter.st"), COUNTER).unwrap();
    let args = [
        "run",
        "counter.st",
        "--realtime",
        "--retain",
        "state.ret",
        "--retain-interval",
        "1h",
        "--trace",
        "--format",
        "json",
    ];
    let mut child = stc(&dir, &args)
        .stdout(Stdio::piped())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    let rx = lines_of(&mut child);
    let mut last = check(&rx.recv_timeout(Duration::from_secs(30)).unwrap());
    let until = Instant::now() + Duration::from_millis(200);
    while let Ok(line) = rx.recv_timeout(until.saturating_duration_since(Instant::now())) {
        last = check(&line);
    }
    let term = Command::new("kill")
        .args(["-TERM", &child.id().to_string()])
        .status()
        .unwrap();
    assert!(term.success());
    let status = child.wait().unwrap();
    assert_eq!(status.code(), Some(0));
    for line in rx.iter() {
        last = check(&line);
    }
    let out = stc(&dir, &args[..5])
        .args(["--cycles", "1", "--format", "json"])
        .output()
        .unwrap();
    let text = String::from_utf8_lossy(&out.stdout);
    assert_eq!(check(text.lines().last().unwrap()), last + 1, "{text}");
    let _ = std::fs::remove_dir_all(&dir);
}
