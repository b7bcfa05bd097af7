//! Running controllers (`stc run --realtime ...`) for the tests: start,
//! wait for their servers, talk HTTP to them, stop them on drop.

#![allow(dead_code)]

use std::io::{BufRead, BufReader, Read, Write};
use std::net::{SocketAddr, TcpStream};
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

pub fn work_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("stc-mon-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// A running `stc run --realtime`, killed when dropped.
pub struct Controller {
    pub child: Child,
    /// Everything it wrote on stderr so far.
    pub stderr: Arc<Mutex<String>>,
    pub monitor: Option<SocketAddr>,
    pub modbus: Option<SocketAddr>,
    pub token: Option<String>,
}

impl Drop for Controller {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

impl Controller {
    /// Starts `stc ARGS` in `dir` and waits (30 s at most) until the
    /// servers it was asked for listen.
    pub fn start(dir: &Path, args: &[&str]) -> Controller {
        let mut child = Command::new(env!("CARGO_BIN_EXE_stc"))
            .current_dir(dir)
            .args(args)
            .stdout(Stdio::null())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap();
        let err = child.stderr.take().unwrap();
        let stderr = Arc::new(Mutex::new(String::new()));
        let sink = Arc::clone(&stderr);
        std::thread::spawn(move || {
            for line in BufReader::new(err).lines() {
                let Ok(line) = line else { break };
                let mut s = sink.lock().unwrap();
                s.push_str(&line);
                s.push('\n');
            }
        });
        let mut c = Controller {
            child,
            stderr,
            monitor: None,
            modbus: None,
            token: None,
        };
        let wants_monitor = args.contains(&"--monitor");
        let wants_modbus = args.contains(&"--modbus");
        let given_token = args.contains(&"--monitor-token");
        let end = Instant::now() + Duration::from_secs(30);
        loop {
            let text = c.stderr.lock().unwrap().clone();
            for line in text.lines() {
                if let Some(a) = line.strip_prefix("note: monitor: listening on http://") {
                    c.monitor = a.trim_end_matches('/').parse().ok();
                }
                if let Some(a) = line.strip_prefix("note: modbus: listening on ") {
                    c.modbus = a.parse().ok();
                }
                if let Some(t) = line.strip_prefix("note: monitor: token ") {
                    c.token = Some(t.to_string());
                }
            }
            let ready = (!wants_monitor
                || (c.monitor.is_some() && (given_token || c.token.is_some())))
                && (!wants_modbus || c.modbus.is_some());
            if ready {
                return c;
            }
            if let Ok(Some(status)) = c.child.try_wait() {
                panic!("stc ended ({status}) before its servers listened: {text}");
            }
            assert!(
                Instant::now() < end,
                "the servers did not start within 30 s: {text}"
            );
            std::thread::sleep(Duration::from_millis(20));
        }
    }

    pub fn stderr(&self) -> String {
        self.stderr.lock().unwrap().clone()
    }

    pub fn addr(&self) -> SocketAddr {
        self.monitor.expect("a monitor")
    }

    /// A GET on the monitor: (status, body).
    pub fn get(&self, path: &str) -> (u16, String) {
        http(self.addr(), "GET", path, &[], b"")
    }

    /// A POST of JSON with the token.
    pub fn post(&self, path: &str, body: &str) -> (u16, String) {
        let auth = format!("Bearer {}", self.token.as_deref().unwrap_or(""));
        http(
            self.addr(),
            "POST",
            path,
            &[
                ("Authorization", &auth),
                ("Content-Type", "application/json"),
            ],
            body.as_bytes(),
        )
    }

    /// The JSON of a GET that must succeed.
    pub fn get_json(&self, path: &str) -> serde_json::Value {
        let (status, body) = self.get(path);
        assert_eq!(status, 200, "GET {path}: {body}");
        serde_json::from_str(&body).unwrap_or_else(|e| panic!("GET {path}: {e}: {body}"))
    }

    /// The value of one variable after the next cycle.
    pub fn value(&self, path: &str) -> serde_json::Value {
        let v = self.get_json(&format!("/api/values?paths={path}"));
        v["values"]
            .as_object()
            .and_then(|m| m.values().next().cloned())
            .unwrap_or_else(|| panic!("no value of {path} in {v}"))
    }
}

/// One HTTP/1.1 request on a fresh connection: (status, body).
pub fn http(
    addr: SocketAddr,
    method: &str,
    path: &str,
    headers: &[(&str, &str)],
    body: &[u8],
) -> (u16, String) {
    let mut s = TcpStream::connect_timeout(&addr, Duration::from_secs(5)).unwrap();
    s.set_read_timeout(Some(Duration::from_secs(15))).unwrap();
    let mut req = format!(
        "{method} {path} HTTP/1.1\r\nHost: {addr}\r\nConnection: close\r\nContent-Length: {}\r\n",
        body.len()
    );
    for (k, v) in headers {
        req.push_str(&format!("{k}: {v}\r\n"));
    }
    req.push_str("\r\n");
    s.write_all(req.as_bytes()).unwrap();
    // A peer may answer (and close) before taking a large body.
    let _ = s.write_all(body);
    let mut raw = Vec::new();
    let _ = s.read_to_end(&mut raw);
    parse_response(&raw)
}

/// The status and the body (de-chunked) of a raw response.
pub fn parse_response(raw: &[u8]) -> (u16, String) {
    let text = String::from_utf8_lossy(raw).to_string();
    let (head, body) = text.split_once("\r\n\r\n").unwrap_or((&text, ""));
    let status = head
        .split_whitespace()
        .nth(1)
        .and_then(|s| s.parse().ok())
        .unwrap_or(0);
    let chunked = head
        .to_ascii_lowercase()
        .contains("transfer-encoding: chunked");
    if !chunked {
        return (status, body.to_string());
    }
    let mut out = String::new();
    let mut rest = body;
    while let Some((size, after)) = rest.split_once("\r\n") {
        let n = usize::from_str_radix(size.trim(), 16).unwrap_or(0);
        if n == 0 || after.len() < n {
            break;
        }
        out.push_str(&after[..n]);
        rest = after[n..].trim_start_matches("\r\n");
    }
    (status, out)
}

/// Polls until `f` holds, for at most `secs` seconds.
pub fn eventually(what: &str, secs: u64, mut f: impl FnMut() -> bool) {
    let end = Instant::now() + Duration::from_secs(secs);
    while Instant::now() < end {
        if f() {
            return;
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    panic!("{what}: not within {secs} s");
}
