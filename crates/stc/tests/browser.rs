//! The monitor's web page in a real browser: headless Chromium (Debian's
//! `chromium`, installed by test.sh) driven over the Chrome DevTools
//! Protocol on loopback. The page shows a value that changes; forcing
//! without the token is refused; with it the program reacts; a release
//! ends the force. Bounded in time; without Chromium the test prints
//! SKIPPED and passes.

#[path = "common/controller.rs"]
mod controller;

use std::io::{BufRead, BufReader};
use std::net::TcpStream;
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

use controller::{work_dir, Controller};
use tungstenite::stream::MaybeTlsStream;
use tungstenite::{Message, WebSocket};

const PLANT: &str = "
PROGRAM Main
VAR_INPUT
    setpoint : INT;
END_VAR
VAR_OUTPUT
    count : DINT;
    doubled : INT;
END_VAR
    count := count + 1;
    doubled := setpoint * 2;
END_PROGRAM
";

fn chromium() -> Option<&'static str> {
    ["chromium", "chromium-browser", "google-chrome"]
        .into_iter()
        .find(|b| {
            Command::new(b)
                .arg("--version")
                .stdout(Stdio::null())
                .stderr(Stdio::null())
                .status()
                .is_ok_and(|s| s.success())
        })
}

/// The browser, killed on drop.
struct Browser {
    child: Child,
    profile: std::path::PathBuf,
}

impl Drop for Browser {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
        let _ = std::fs::remove_dir_all(&self.profile);
    }
}

/// A DevTools session on one page.
struct Page {
    ws: WebSocket<MaybeTlsStream<TcpStream>>,
    session: String,
    next_id: u64,
}

impl Page {
    fn call(
        &mut self,
        method: &str,
        params: serde_json::Value,
        session: bool,
    ) -> serde_json::Value {
        self.next_id += 1;
        let id = self.next_id;
        let mut msg = serde_json::json!({"id": id, "method": method, "params": params});
        if session {
            msg["sessionId"] = self.session.clone().into();
        }
        self.ws.send(Message::Text(msg.to_string().into())).unwrap();
        let end = Instant::now() + Duration::from_secs(30);
        loop {
            assert!(Instant::now() < end, "{method}: no answer within 30 s");
            let Message::Text(t) = self.ws.read().unwrap() else {
                continue;
            };
            let v: serde_json::Value = serde_json::from_str(t.as_str()).unwrap();
            if v["id"] == id {
                assert!(v.get("error").is_none(), "{method}: {v}");
                return v["result"].clone();
            }
        }
    }

    /// Evaluates JavaScript in the page (promises awaited).
    fn eval(&mut self, expr: &str) -> serde_json::Value {
        let r = self.call(
            "Runtime.evaluate",
            serde_json::json!({"expression": expr, "awaitPromise": true, "returnByValue": true}),
            true,
        );
        assert!(r.get("exceptionDetails").is_none(), "{expr}: {r}");
        r["result"]["value"].clone()
    }

    /// Waits until `expr` is true in the page.
    fn until(&mut self, what: &str, expr: &str) {
        let end = Instant::now() + Duration::from_secs(20);
        while Instant::now() < end {
            if self.eval(expr) == serde_json::Value::Bool(true) {
                return;
            }
            std::thread::sleep(Duration::from_millis(50));
        }
        let html = self.eval("document.body.innerText");
        panic!("{what}: not within 20 s; the page shows:\n{html}");
    }

    fn text(&mut self, path: &str) -> String {
        self.eval(&format!(
            "(document.querySelector('tr[data-path=\"{path}\"] .value') || {{}}).textContent || ''"
        ))
        .as_str()
        .unwrap_or("")
        .to_string()
    }
}

fn launch(binary: &str, url: &str) -> (Browser, Page) {
    let profile = work_dir("chromium-profile");
    let mut child = Command::new(binary)
        .args([
            "--headless",
            "--no-sandbox",
            "--disable-gpu",
            "--disable-quic",
            "--no-first-run",
            "--disable-background-networking",
            "--disable-component-update",
            "--disable-sync",
            "--disable-dev-shm-usage",
            "--remote-debugging-address=127.0.0.1",
            "--remote-debugging-port=0",
            "--window-size=1400,1000",
        ])
        .arg(format!("--user-data-dir={}", profile.display()))
        .arg("about:blank")
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let err = child.stderr.take().unwrap();
    let browser = Browser { child, profile };
    let (tx, rx) = std::sync::mpsc::channel();
    std::thread::spawn(move || {
        for line in BufReader::new(err).lines() {
            let Ok(line) = line else { break };
            if let Some(i) = line.find("ws://") {
                let _ = tx.send(line[i..].trim().to_string());
            }
        }
    });
    let endpoint = rx
        .recv_timeout(Duration::from_secs(30))
        .expect("chromium did not open its DevTools endpoint within 30 s");
    let (ws, _) = tungstenite::connect(endpoint).unwrap();
    if let MaybeTlsStream::Plain(s) = ws.get_ref() {
        s.set_read_timeout(Some(Duration::from_secs(30))).unwrap();
    }
    let mut page = Page {
        ws,
        session: String::new(),
        next_id: 0,
    };
    let target = page.call(
        "Target.createTarget",
        serde_json::json!({"url": url}),
        false,
    );
    let attached = page.call(
        "Target.attachToTarget",
        serde_json::json!({"targetId": target["targetId"], "flatten": true}),
        false,
    );
    page.session = attached["sessionId"].as_str().unwrap().to_string();
    (browser, page)
}

#[test]
fn the_page_shows_live_values_and_forces_with_the_token() {
    let Some(binary) = chromium() else {
        println!("SKIPPED: the browser test needs chromium (test.sh installs it with apt-get)");
        eprintln!("SKIPPED: the browser test needs chromium (test.sh installs it with apt-get)");
        return;
    };
    let started = Instant::now();
    let dir = work_dir("browser");
    std::fs::write(dir.join("plant.st"), PLANT).unwrap();
    let c = Controller::start(
        &dir,
        &[
            "run",
            "plant.st",
            "--realtime",
            "--tick",
            "10ms",
            "--monitor",
            "127.0.0.1:0",
            "--monitor-token",
            "letmein",
        ],
    );
    let (_browser, mut page) = launch(binary, &format!("http://{}/", c.addr()));

    // The list and a live value that changes.
    page.until(
        "the count is shown",
        "/^[0-9]+$/.test((document.querySelector('tr[data-path=\"Main.count\"] .value')||{}).textContent||'')",
    );
    let a: i64 = page.text("Main.count").parse().unwrap();
    page.until(
        "the count changes",
        &format!(
            "+document.querySelector('tr[data-path=\"Main.count\"] .value').textContent > {a}"
        ),
    );
    page.until(
        "the stream is live",
        "document.querySelector('#status').textContent === 'live'",
    );

    // Forcing without the token: refused, and nothing changes.
    let force = "(() => { const tr = document.querySelector('tr[data-path=\"Main.setpoint\"]'); \
                 tr.querySelector('.force-input').value = '21'; tr.querySelector('.force-btn').click(); return true; })()";
    page.eval("document.querySelector('#token').value = ''");
    page.eval(force);
    page.until(
        "the force is refused",
        "document.querySelector('#message').textContent.startsWith('force refused (401)')",
    );
    assert_eq!(page.text("Main.doubled"), "0");
    page.eval("document.querySelector('#token').value = 'wrong'");
    page.eval(force);
    page.until(
        "the wrong token is refused",
        "document.querySelector('#message').textContent.startsWith('force refused (403)')",
    );
    assert_eq!(c.get_json("/api/forces")["forces"], serde_json::json!([]));

    // With the token: the program reacts, the row shows the force.
    page.eval("document.querySelector('#token').value = 'letmein'");
    page.eval(force);
    page.until(
        "the force is accepted",
        "document.querySelector('#message').textContent === 'forced Main.setpoint := 21'",
    );
    page.until(
        "the program reacts",
        "document.querySelector('tr[data-path=\"Main.doubled\"] .value').textContent === '42'",
    );
    page.until(
        "the row is marked forced",
        "document.querySelector('tr[data-path=\"Main.setpoint\"]').classList.contains('forced')",
    );
    assert_eq!(c.value("Main.doubled"), 42);

    // The trend plots a ticked variable; the histogram and the task
    // statistics are drawn.
    page.eval("document.querySelector('tr[data-path=\"Main.count\"] .trend-check').click()");
    page.until(
        "the trend has points",
        "state.trend.get('Main.count').length > 5",
    );
    page.until(
        "the statistics are shown",
        "document.querySelectorAll('#stats tbody tr').length >= 1 && \
         +document.querySelector('#stats tbody tr td:nth-child(2)').textContent > 0",
    );
    let shot = page.call(
        "Page.captureScreenshot",
        serde_json::json!({"format": "png"}),
        true,
    );
    if let Some(png) = shot["data"].as_str() {
        let _ = std::fs::write(std::env::temp_dir().join("stc-monitor-page.png.b64"), png);
    }

    // Released: the program's own input again (it keeps the value).
    page.eval("document.querySelector('tr[data-path=\"Main.setpoint\"] .release-btn').click()");
    page.until(
        "the force is released",
        "!document.querySelector('tr[data-path=\"Main.setpoint\"]').classList.contains('forced')",
    );
    assert_eq!(c.get_json("/api/forces")["forces"], serde_json::json!([]));
    assert!(
        started.elapsed() < Duration::from_secs(120),
        "{:?}",
        started.elapsed()
    );
    drop(c);
    let _ = std::fs::remove_dir_all(&dir);
}
