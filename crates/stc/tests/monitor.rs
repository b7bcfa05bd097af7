//! The monitor of the real-time controller (`stc run --realtime --monitor
//! 127.0.0.1:0`) against a running process: list, read, stream, force and
//! release variables, the token, the statistics, malformed requests; the
//! real-time watchdog and overruns; the Modbus TCP client channels of the
//! allocation map against the stc Modbus server. Every test starts what it
//! needs and stops it by itself.

#[path = "common/controller.rs"]
mod controller;

use std::time::{Duration, Instant};

use controller::{eventually, http, work_dir, Controller};

/// `doubled` follows `setpoint`; `count` counts cycles.
const PLANT: &str = "
PROGRAM Main
VAR_INPUT
    setpoint : INT;
END_VAR
VAR_OUTPUT
    count : DINT;
    doubled : INT;
END_VAR
VAR
    name : STRING[16] := 'plant';
    level : REAL;
    tmr : TON;
    arr : ARRAY[1..3] OF INT;
END_VAR
VAR CONSTANT
    LIMIT : INT := 10;
END_VAR
    count := count + 1;
    doubled := setpoint * 2;
    level := INT_TO_REAL(setpoint) / 4.0;
    arr[1] := setpoint;
END_PROGRAM

CONFIGURATION Plant
    RESOURCE Cpu ON PLC
        TASK fast (INTERVAL := T#5ms, PRIORITY := 1);
        PROGRAM Main WITH fast : Main;
    END_RESOURCE
END_CONFIGURATION
";

fn start(name: &str, extra: &[&str]) -> (Controller, std::path::PathBuf) {
    let dir = work_dir(name);
    std::fs::write(dir.join("plant.st"), PLANT).unwrap();
    let mut args = vec!["run", "plant.st", "--realtime", "--monitor", "127.0.0.1:0"];
    args.extend_from_slice(extra);
    (Controller::start(&dir, &args), dir)
}

type Ws = tungstenite::WebSocket<tungstenite::stream::MaybeTlsStream<std::net::TcpStream>>;

/// The next text message of a WebSocket, as JSON.
fn next(ws: &mut Ws) -> serde_json::Value {
    loop {
        if let tungstenite::Message::Text(t) = ws.read().unwrap() {
            return serde_json::from_str(t.as_str()).unwrap();
        }
    }
}

fn int(v: &serde_json::Value) -> i64 {
    v.as_i64().unwrap_or_else(|| panic!("not an integer: {v}"))
}

#[test]
fn the_api_lists_reads_forces_and_releases_variables() {
    let (c, dir) = start("api", &[]);
    let token = c.token.clone().expect("a token printed at start");
    assert_eq!(token.len(), 32, "{token}");

    // The list: paths in the --watch syntax, types, forcible, forced.
    let list = c.get_json("/api/variables");
    let vars = list["variables"].as_array().unwrap();
    let find = |p: &str| {
        vars.iter()
            .find(|v| v["path"] == p)
            .unwrap_or_else(|| panic!("{p} is not listed: {list}"))
    };
    assert_eq!(find("Main.count")["type"], "DINT");
    assert_eq!(find("Main.count")["forcible"], true);
    assert_eq!(find("Main.tmr.PT")["type"], "TIME");
    assert_eq!(find("Main.arr")["forcible"], false);
    assert_eq!(find("Main.arr[2]")["type"], "INT");
    assert_eq!(find("Main.LIMIT")["forcible"], false);
    assert_eq!(find("Main.name")["type"], "STRING[16]");

    // Reads: values as --format json prints them, after a cycle.
    let v = c.get_json("/api/values?paths=Main.count,main.name,Main.tmr,Main.arr");
    assert!(int(&v["cycle"]) >= 1, "{v}");
    assert_eq!(v["values"]["Main.name"], "plant");
    assert_eq!(v["values"]["Main.tmr"]["PT"], "T#0s");
    assert_eq!(v["values"]["Main.arr"], serde_json::json!([0, 0, 0]));
    let first = int(&v["values"]["Main.count"]);
    eventually("the count moves", 10, || {
        int(&c.value("Main.count")) > first
    });

    // Forcing an input: the program reacts to the forced value.
    let (status, body) = c.post("/api/force", r#"{"path":"main.SETPOINT","value":"21"}"#);
    assert_eq!(status, 200, "{body}");
    assert_eq!(
        serde_json::from_str::<serde_json::Value>(&body).unwrap()["forced"],
        "Main.setpoint"
    );
    eventually("doubled follows the forced setpoint", 10, || {
        c.value("Main.doubled") == 42
    });
    assert_eq!(c.value("Main.level"), 5.25);
    // Forcing what the program writes: nobody outside sees another value.
    let (status, body) = c.post("/api/force", r#"{"path":"Main.count","value":7}"#);
    assert_eq!(status, 200, "{body}");
    for _ in 0..5 {
        assert_eq!(c.value("Main.count"), 7);
    }
    let forced = c.get_json("/api/forces");
    assert_eq!(
        forced["forces"],
        serde_json::json!([{"path":"Main.setpoint","value":"21"},{"path":"Main.count","value":"7"}])
    );
    let list = c.get_json("/api/variables");
    let count = list["variables"]
        .as_array()
        .unwrap()
        .iter()
        .find(|v| v["path"] == "Main.count")
        .unwrap()
        .clone();
    assert_eq!(count["forced"], true);
    let v = c.get_json("/api/values?paths=Main.count");
    assert_eq!(
        v["forced"],
        serde_json::json!(["Main.setpoint", "Main.count"])
    );
    // A force of a string and a time.
    assert_eq!(
        c.post("/api/force", r#"{"path":"Main.name","value":"'forced'"}"#)
            .0,
        200
    );
    assert_eq!(
        c.post(
            "/api/force",
            r#"{"path":"Main.tmr.PT","value":"T#1s500ms"}"#
        )
        .0,
        200
    );
    assert_eq!(c.value("Main.name"), "forced");
    assert_eq!(c.value("Main.tmr.PT"), "T#1s500ms");

    // Released: the program writes the variable again.
    let (status, body) = c.post("/api/unforce", r#"{"path":"Main.count"}"#);
    assert_eq!(status, 200, "{body}");
    eventually("the count moves on from 7", 10, || {
        int(&c.value("Main.count")) > 8
    });
    let (status, body) = c.post("/api/unforce", r#"{"path":"Main.count"}"#);
    assert_eq!(status, 409, "{body}");
    let (status, body) = c.post("/api/unforce", r#"{"all":true}"#);
    assert_eq!((status, body.as_str()), (200, r#"{"released":3}"#));
    assert_eq!(c.get_json("/api/forces")["forces"], serde_json::json!([]));

    // Statistics.
    let s = c.get_json("/api/stats");
    assert!(int(&s["cycles"]) > 0, "{s}");
    assert_eq!(s["tick_ns"], 5_000_000);
    assert!(
        int(&s["cycle"]["max_ns"]) >= int(&s["cycle"]["min_ns"]),
        "{s}"
    );
    assert!(s["cycle"]["mean_ns"].is_u64(), "{s}");
    assert!(s["jitter"]["max_ns"].is_u64(), "{s}");
    assert!(s["overruns"].is_u64(), "{s}");
    assert_eq!(s["watchdog_faults"], 0);
    let task = &s["tasks"][0];
    assert_eq!(task["name"], "fast");
    assert_eq!(task["interval_ns"], 5_000_000);
    assert!(int(&task["runs"]) > 0, "{s}");
    assert_eq!(
        s["histogram"]["counts"]
            .as_array()
            .unwrap()
            .iter()
            .map(int)
            .sum::<i64>(),
        int(&s["cycles"]),
        "{s}"
    );
    let info = c.get_json("/api/info");
    assert_eq!(info["running"], "Plant");
    assert_eq!(info["tick"], "T#5ms");

    // The page.
    let (status, page) = c.get("/");
    assert_eq!(status, 200);
    assert!(page.contains("<title>stc monitor</title>"));
    drop(c);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn forcing_needs_the_token() {
    let (c, dir) = start("token", &["--monitor-token", "s3cret"]);
    assert!(c.token.is_none());
    assert!(!c.stderr().contains("s3cret"), "the given token is printed");
    let body = r#"{"path":"Main.setpoint","value":"5"}"#;
    // No token: 401 with WWW-Authenticate.
    let (status, text) = http(
        c.addr(),
        "POST",
        "/api/force",
        &[("Content-Type", "application/json")],
        body.as_bytes(),
    );
    assert_eq!(status, 401, "{text}");
    assert!(text.contains("Authorization: Bearer"), "{text}");
    // A wrong token, or the right one in the wrong form: 403.
    for auth in ["Bearer s3cre", "Bearer s3cret2", "s3cret", "Basic czNjcmV0"] {
        let (status, text) = http(
            c.addr(),
            "POST",
            "/api/force",
            &[("Authorization", auth)],
            body.as_bytes(),
        );
        assert_eq!(status, 403, "{auth}: {text}");
    }
    let (status, _) = http(c.addr(), "POST", "/api/unforce", &[], br#"{"all":true}"#);
    assert_eq!(status, 401);
    // Nothing was forced.
    assert_eq!(c.get_json("/api/forces")["forces"], serde_json::json!([]));
    assert_eq!(c.value("Main.doubled"), 0);
    // The right token.
    let (status, text) = http(
        c.addr(),
        "POST",
        "/api/force",
        &[("Authorization", "Bearer s3cret")],
        body.as_bytes(),
    );
    assert_eq!(status, 200, "{text}");
    eventually("doubled = 10", 10, || c.value("Main.doubled") == 10);
    drop(c);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn malformed_requests_are_clear_errors_that_cost_only_themselves() {
    let (mut c, dir) = start("bad", &["--monitor-token", "tok"]);
    c.token = Some("tok".into());
    let error = |(status, body): (u16, String), want: u16, has: &str| {
        assert_eq!(status, want, "{body}");
        let v: serde_json::Value =
            serde_json::from_str(&body).unwrap_or_else(|e| panic!("{e}: {body}"));
        let msg = v["error"].as_str().unwrap_or_else(|| panic!("{body}"));
        assert!(msg.contains(has), "`{msg}` does not say `{has}`");
    };
    error(c.post("/api/force", "{not json"), 400, "not JSON");
    error(c.post("/api/force", "[1,2]"), 400, "JSON object");
    error(
        c.post("/api/force", r#"{"value":"1"}"#),
        400,
        "`path` is missing",
    );
    error(
        c.post("/api/force", r#"{"path":"Main.count"}"#),
        400,
        "`value` is missing",
    );
    error(
        c.post("/api/force", r#"{"path":"Main.count","value":[1]}"#),
        400,
        "`value` must be",
    );
    error(
        c.post("/api/force", r#"{"path":"Main.nope","value":"1"}"#),
        404,
        "unknown variable `Main.nope`",
    );
    error(
        c.post("/api/force", r#"{"path":"Main..x[","value":"1"}"#),
        404,
        "Main..x[",
    );
    error(
        c.post("/api/force", r#"{"path":"Main.count","value":"TRUE_ish"}"#),
        422,
        "cannot be read as DINT",
    );
    error(
        c.post("/api/force", r#"{"path":"Main.setpoint","value":"99999"}"#),
        422,
        "INT",
    );
    error(
        c.post("/api/force", r#"{"path":"Main.LIMIT","value":"1"}"#),
        422,
        "CONSTANT",
    );
    error(
        c.post("/api/force", r#"{"path":"Main.tmr","value":"1"}"#),
        422,
        "only an elementary",
    );
    error(
        c.post("/api/force", r#"{"path":"Main.arr[9]","value":"1"}"#),
        404,
        "outside its bounds",
    );
    error(c.get("/api/values?paths=Main.zz"), 404, "unknown variable");
    error(c.get("/api/nothing"), 404, "no such endpoint");
    error(c.get("/api/ws"), 400, "WebSocket");
    // A huge body: refused whole, not read into memory.
    let huge = format!(
        r#"{{"path":"Main.count","value":"{}"}}"#,
        "1".repeat(1 << 20)
    );
    let auth = [("Authorization", "Bearer tok")];
    let (status, body) = http(c.addr(), "POST", "/api/force", &auth, huge.as_bytes());
    assert_eq!(status, 413, "{body}");
    // Not UTF-8, a request line that is no HTTP, a half-sent request:
    // each costs its own connection.
    let (status, _) = http(c.addr(), "POST", "/api/force", &auth, &[0xff, 0xfe, 0x00]);
    assert_eq!(status, 400);
    {
        use std::io::{Read, Write};
        let mut s = std::net::TcpStream::connect(c.addr()).unwrap();
        s.set_read_timeout(Some(Duration::from_secs(10))).unwrap();
        s.write_all(b"\x16\x03\x01garbage that is no request\r\n\r\n")
            .unwrap();
        let mut out = Vec::new();
        let _ = s.read_to_end(&mut out);
        let mut half = std::net::TcpStream::connect(c.addr()).unwrap();
        half.write_all(b"GET /api/stats HTTP/1.1\r\nHost: x\r\n")
            .unwrap();
        // Still served, forces still work, the program still runs.
        let before = int(&c.value("Main.count"));
        assert_eq!(
            c.post("/api/force", r#"{"path":"Main.setpoint","value":3}"#)
                .0,
            200
        );
        eventually("doubled = 6", 10, || c.value("Main.doubled") == 6);
        assert!(int(&c.value("Main.count")) > before);
        drop(half);
    }
    assert!(c.child.try_wait().unwrap().is_none(), "stc ended");
    drop(c);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn the_websocket_streams_values_and_takes_new_watch_lists() {
    use tungstenite::Message;
    let (c, dir) = start("ws", &[]);
    let url = format!("ws://{}/api/ws?paths=Main.count&interval=0", c.addr());
    let (mut ws, _) = tungstenite::connect(url).unwrap();
    if let tungstenite::stream::MaybeTlsStream::Plain(s) = ws.get_ref() {
        s.set_read_timeout(Some(Duration::from_secs(10))).unwrap();
    }
    let a = next(&mut ws);
    let b = next(&mut ws);
    assert!(int(&b["cycle"]) > int(&a["cycle"]), "{a} {b}");
    assert!(int(&b["values"]["Main.count"]) > int(&a["values"]["Main.count"]));
    // A new watch list.
    ws.send(Message::Text(
        r#"{"watch":["Main.doubled","Main.name"]}"#.into(),
    ))
    .unwrap();
    let end = Instant::now() + Duration::from_secs(10);
    loop {
        let m = next(&mut ws);
        if m["values"].get("Main.name").is_some() {
            assert_eq!(m["values"]["Main.name"], "plant");
            assert!(m["values"].get("Main.count").is_none());
            break;
        }
        assert!(Instant::now() < end, "the watch list did not change");
    }
    // A message it cannot use: an error message, and the stream goes on.
    ws.send(Message::Text("{\"watch\":[\"Main.nope\"]}".into()))
        .unwrap();
    let end = Instant::now() + Duration::from_secs(10);
    loop {
        let m = next(&mut ws);
        if let Some(e) = m.get("error") {
            assert!(e.as_str().unwrap().contains("unknown variable"), "{m}");
            break;
        }
        assert!(Instant::now() < end, "no error answer");
    }
    ws.send(Message::Text("garbage".into())).unwrap();
    ws.send(Message::Binary(vec![1, 2, 3].into())).unwrap();
    let mut errors = 0;
    let mut values = 0;
    while errors < 2 || values < 2 {
        let m = next(&mut ws);
        if m.get("error").is_some() {
            errors += 1;
        } else {
            values += 1;
        }
        assert!(Instant::now() < end + Duration::from_secs(10));
    }
    // A rate limit: 200 ms between messages.
    let url = format!("ws://{}/api/ws?paths=Main.count&interval=200ms", c.addr());
    let (mut slow, _) = tungstenite::connect(url).unwrap();
    let t0 = Instant::now();
    let x = next(&mut slow);
    let y = next(&mut slow);
    let z = next(&mut slow);
    assert!(
        t0.elapsed() >= Duration::from_millis(350),
        "{:?}",
        t0.elapsed()
    );
    assert!(int(&z["cycle"]) - int(&x["cycle"]) >= 40, "{x} {y} {z}");
    // Bad parameters are refused before the upgrade.
    let bad = format!("ws://{}/api/ws?paths=Main.nope", c.addr());
    assert!(tungstenite::connect(bad).is_err());
    // A message over 64 KiB closes its own connection, nothing else.
    let url = format!("ws://{}/api/ws?paths=Main.count", c.addr());
    let (mut big, _) = tungstenite::connect(url).unwrap();
    if let tungstenite::stream::MaybeTlsStream::Plain(s) = big.get_ref() {
        s.set_read_timeout(Some(Duration::from_secs(10))).unwrap();
    }
    let _ = big.send(Message::Text("x".repeat(100_000).into()));
    let end = Instant::now() + Duration::from_secs(10);
    loop {
        match big.read() {
            Ok(Message::Close(_)) | Err(_) => break,
            Ok(_) => assert!(Instant::now() < end, "still open"),
        }
    }
    let before = int(&next(&mut ws)["cycle"]);
    assert!(int(&next(&mut ws)["cycle"]) > before);
    let _ = ws.close(None);
    drop(c);
    let _ = std::fs::remove_dir_all(&dir);
}

/// A program that runs away: the watchdog stops it in real time as in
/// simulation, with the report of the last completed cycle.
#[test]
fn the_watchdog_stops_a_runaway_program_in_real_time() {
    let dir = work_dir("watchdog");
    std::fs::write(
        dir.join("loop.st"),
        "PROGRAM Main
VAR_OUTPUT n : DINT; END_VAR
VAR i : DINT; END_VAR
    n := n + 1;
    IF n = 3 THEN
        WHILE TRUE DO i := i + 1; END_WHILE;
    END_IF;
END_PROGRAM
",
    )
    .unwrap();
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_stc"))
        .current_dir(&dir)
        .args([
            "run",
            "loop.st",
            "--realtime",
            "--tick",
            "5ms",
            "--max-steps",
            "100000",
            "--format",
            "json",
            "--cycles",
            "10",
        ])
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    let text = String::from_utf8_lossy(&out.stdout);
    assert_eq!(out.status.code(), Some(3), "{err}");
    assert!(err.contains("fault: watchdog in Main (Main)"), "{err}");
    assert!(
        text.contains(r#"{"cycle":2,"time":"T#5ms","values":{"Main.n":2}}"#),
        "{text}"
    );
    assert!(text.contains(r#""fault":{"kind":"watchdog""#), "{text}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// Cycles longer than the tick: counted in the statistics, warned about
/// at most once a second.
#[test]
fn overruns_are_counted_and_their_warnings_rate_limited() {
    let dir = work_dir("overrun");
    std::fs::write(
        dir.join("slow.st"),
        "PROGRAM Main
VAR_OUTPUT n : DINT; END_VAR
VAR i : DINT; x : DINT; END_VAR
    n := n + 1;
    FOR i := 1 TO 500000 DO x := x + i MOD 7; END_FOR;
END_PROGRAM

CONFIGURATION Plant
    RESOURCE Cpu ON PLC
        TASK busy (INTERVAL := T#1ms, PRIORITY := 1);
        PROGRAM Main WITH busy : Main;
    END_RESOURCE
END_CONFIGURATION
",
    )
    .unwrap();
    let c = Controller::start(
        &dir,
        &["run", "slow.st", "--realtime", "--monitor", "127.0.0.1:0"],
    );
    let t0 = Instant::now();
    eventually("overruns are counted", 20, || {
        c.get_json("/api/stats")["overruns"].as_u64().unwrap_or(0) >= 20
    });
    std::thread::sleep(Duration::from_millis(1500));
    let s = c.get_json("/api/stats");
    let secs = t0.elapsed().as_secs() + 2;
    let warnings = c
        .stderr()
        .lines()
        .filter(|l| l.starts_with("warning: overrun:"))
        .count() as u64;
    assert!(warnings >= 1, "{}", c.stderr());
    assert!(
        warnings <= secs + 1,
        "{warnings} warnings in {secs} s: {}",
        c.stderr()
    );
    assert!(
        c.stderr().contains("more overruns since the last warning"),
        "{}",
        c.stderr()
    );
    assert!(int(&s["overruns"]) >= 20, "{s}");
    // The task's own figures: each run longer than its 1 ms interval.
    let task = &s["tasks"][0];
    assert_eq!(task["name"], "busy");
    assert!(int(&task["overruns"]) >= 20, "{s}");
    assert!(int(&task["exec"]["min_ns"]) > 1_000_000, "{s}");
    assert!(
        int(&task["response"]["max_ns"]) >= int(&task["exec"]["max_ns"]),
        "{s}"
    );
    drop(c);
    let _ = std::fs::remove_dir_all(&dir);
}

/// The remote device: the plant of the Modbus tests, on the stc Modbus
/// server (coil 0 = `start`, coil 1 = `lamp := start`, input registers
/// 10-11 = the cycle count).
const DEVICE: &str = "
PROGRAM Main
VAR
    start    AT %QX0.0 : BOOL;
    lamp     AT %QX0.1 : BOOL;
    setpoint AT %QW0 : INT;
    count : DINT;
END_VAR
    count := count + 1;
    lamp := start;
END_PROGRAM
";

const DEVICE_MAP: &str = "
[[modbus]]
variable = \"Main.count\"
table = \"input\"
address = 10
";

/// The controller that polls it.
const POLLER: &str = "
PROGRAM Poll
VAR_OUTPUT
    remote_count : DINT;
    lamp : BOOL;
    cycles : DINT;
END_VAR
VAR
    cmd : BOOL;
    sp : INT;
END_VAR
    cycles := cycles + 1;
END_PROGRAM
";

fn device(dir: &std::path::Path, port: u16) -> Controller {
    let addr = format!("127.0.0.1:{port}");
    Controller::start(
        dir,
        &[
            "run",
            "device.st",
            "--realtime",
            "--tick",
            "5ms",
            "--io-map",
            "device.toml",
            "--modbus",
            &addr,
        ],
    )
}

#[test]
fn modbus_client_channels_poll_a_remote_device_and_survive_its_loss() {
    let dir = work_dir("client");
    std::fs::write(dir.join("device.st"), DEVICE).unwrap();
    std::fs::write(dir.join("device.toml"), DEVICE_MAP).unwrap();
    std::fs::write(dir.join("poll.st"), POLLER).unwrap();
    let dev = device(&dir, 0);
    let port = dev.modbus.unwrap().port();
    let map = format!(
        "
[[client]]
device = \"127.0.0.1:{port}\"
table = \"input\"
address = 10
count = 2
variables = [\"Poll.remote_count\"]
poll = \"20ms\"

[[client]]
device = \"127.0.0.1:{port}\"
unit = 1
table = \"coil\"
address = 0
variables = [\"Poll.cmd\"]
write = true
poll = \"20ms\"

[[client]]
device = \"127.0.0.1:{port}\"
table = \"coil\"
address = 1
variables = [\"Poll.lamp\"]
poll = \"20ms\"
"
    );
    std::fs::write(dir.join("poll.toml"), map).unwrap();
    let mut poller = Controller::start(
        &dir,
        &[
            "run",
            "poll.st",
            "--realtime",
            "--tick",
            "5ms",
            "--io-map",
            "poll.toml",
            "--monitor",
            "127.0.0.1:0",
            "--monitor-token",
            "t",
        ],
    );
    poller.token = Some("t".into());
    // Reading: the device's cycle count arrives and moves.
    eventually("the remote count arrives", 10, || {
        int(&poller.value("Poll.remote_count")) > 0
    });
    let a = int(&poller.value("Poll.remote_count"));
    eventually("the remote count moves", 10, || {
        int(&poller.value("Poll.remote_count")) > a
    });
    // Writing: the poller's cmd goes to the device's coil 0, the device's
    // lamp follows, and the poller reads the lamp back.
    assert_eq!(poller.value("Poll.lamp"), false);
    assert_eq!(
        poller
            .post("/api/force", r#"{"path":"Poll.cmd","value":true}"#)
            .0,
        200
    );
    eventually("the remote lamp follows cmd", 10, || {
        poller.value("Poll.lamp") == true
    });
    // The device goes away: reported once, the cycles go on.
    drop(dev);
    let c0 = int(&poller.value("Poll.cycles"));
    eventually("the loss is reported", 10, || {
        poller.stderr().contains("connection lost") || poller.stderr().contains("cannot connect")
    });
    std::thread::sleep(Duration::from_millis(2500));
    let c1 = int(&poller.value("Poll.cycles"));
    assert!(c1 - c0 > 200, "the cycles stalled: {c0} -> {c1}");
    let err = poller.stderr();
    for ch in ["input register 10..11", "coil 0..0", "coil 1..1"] {
        let n = err
            .lines()
            .filter(|l| l.starts_with("warning:") && l.contains(ch))
            .count();
        assert_eq!(n, 1, "`{ch}` reported {n} times: {err}");
    }
    // The last values stay.
    assert_eq!(poller.value("Poll.lamp"), true);
    // It comes back on the same port: reconnected, reported once.
    let dev = device(&dir, port);
    eventually("reconnected", 15, || {
        poller.stderr().matches("connected again").count() == 3
    });
    // The count moves again (it stood still at its last value while the
    // device was away), and the coil is written again.
    let b = int(&poller.value("Poll.remote_count"));
    eventually("the new count arrives", 10, || {
        int(&poller.value("Poll.remote_count")) != b
    });
    eventually("the new lamp follows cmd", 10, || {
        poller.value("Poll.lamp") == true
    });
    drop(dev);
    drop(poller);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn client_channel_mistakes_are_exit_2_before_anything_runs() {
    let dir = work_dir("clientmap");
    std::fs::write(dir.join("poll.st"), POLLER).unwrap();
    let cases = [
        (
            "[[client]]\ndevice = \"localhost\"\ntable = \"input\"\naddress = 0\nvariables = [\"Poll.cycles\"]\n",
            "bad.toml:2: device `localhost`: expected HOST:PORT",
        ),
        (
            "[[client]]\ndevice = \"h:1\"\ntable = \"input\"\naddress = 0\nvariables = [\"Poll.cycles\"]\nwrite = true\n",
            "bad.toml:3: `write = true` needs a coil or holding register",
        ),
        (
            "[[client]]\ndevice = \"h:1\"\ntable = \"coil\"\naddress = 0\nvariables = [\"Poll.cycles\"]\n",
            "bad.toml:5: `Poll.cycles` is DINT: a coil holds a BOOL",
        ),
    ];
    for (text, expected) in cases {
        std::fs::write(dir.join("bad.toml"), text).unwrap();
        let out = std::process::Command::new(env!("CARGO_BIN_EXE_stc"))
            .current_dir(&dir)
            .args([
                "run",
                "poll.st",
                "--realtime",
                "--io-map",
                "bad.toml",
                "--cycles",
                "1",
            ])
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{text}: {err}");
        assert!(
            err.contains(&format!("\nerror: {expected}")),
            "{text}: {err}"
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}
