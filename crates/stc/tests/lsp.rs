//! `stc lsp`: a test client speaking the protocol (Content-Length framed
//! JSON-RPC) to the real server process.

use std::io::{BufRead, BufReader, Read, Write};
use std::process::{Child, ChildStdin, ChildStdout, Command, Stdio};

use serde_json::{json, Value};

struct Client {
    child: Child,
    stdin: ChildStdin,
    stdout: BufReader<ChildStdout>,
    next_id: i64,
    /// Notifications received while waiting for responses.
    notifications: Vec<Value>,
}

impl Client {
    fn start() -> Client {
        let mut child = Command::new(env!("CARGO_BIN_EXE_stc"))
            .arg("lsp")
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .stderr(Stdio::inherit())
            .spawn()
            .expect("stc lsp starts");
        let stdin = child.stdin.take().unwrap();
        let stdout = BufReader::new(child.stdout.take().unwrap());
        Client {
            child,
            stdin,
            stdout,
            next_id: 1,
            notifications: Vec::new(),
        }
    }

    fn send(&mut self, msg: Value) {
        let body = msg.to_string();
        write!(self.stdin, "Content-Length: {}\r\n\r\n{body}", body.len()).unwrap();
        self.stdin.flush().unwrap();
    }

    fn read(&mut self) -> Value {
        let mut len = 0usize;
        loop {
            let mut line = String::new();
            assert!(
                self.stdout.read_line(&mut line).unwrap() > 0,
                "server closed"
            );
            let line = line.trim_end();
            if line.is_empty() {
                break;
            }
            if let Some(v) = line.strip_prefix("Content-Length: ") {
                len = v.parse().unwrap();
            }
        }
        let mut body = vec![0u8; len];
        self.stdout.read_exact(&mut body).unwrap();
        serde_json::from_slice(&body).unwrap()
    }

    fn notify(&mut self, method: &str, params: Value) {
        self.send(json!({"jsonrpc": "2.0", "method": method, "params": params}));
    }

    /// Sends a request and returns its response (result or error).
    fn request(&mut self, method: &str, params: Value) -> Value {
        let id = self.next_id;
        self.next_id += 1;
        self.send(json!({"jsonrpc": "2.0", "id": id, "method": method, "params": params}));
        loop {
            let m = self.read();
            if m.get("id") == Some(&json!(id)) {
                return m;
            }
            self.notifications.push(m);
        }
    }

    /// The next diagnostics published for `uri`.
    fn diagnostics(&mut self, uri: &str) -> Vec<Value> {
        loop {
            if let Some(i) = self.notifications.iter().position(|n| {
                n["method"] == "textDocument/publishDiagnostics" && n["params"]["uri"] == uri
            }) {
                let n = self.notifications.remove(i);
                return n["params"]["diagnostics"].as_array().unwrap().clone();
            }
            let m = self.read();
            self.notifications.push(m);
        }
    }
}

const URI: &str = "file:///virtual/plant.st";

fn pos(line: u32, character: u32) -> Value {
    json!({"textDocument": {"uri": URI}, "position": {"line": line, "character": character}})
}

const TEXT: &str = "\
TYPE
    Mode : (Off, Auto);
END_TYPE

(* Counts rising edges. *)
FUNCTION_BLOCK Counter
    VAR_INPUT
        pulse : BOOL;
    END_VAR
    VAR_OUTPUT
        count : INT; (* edges so far *)
    END_VAR
    IF pulse THEN
        count := count + 1;
    END_IF;
END_FUNCTION_BLOCK

PROGRAM Main
    VAR
        c : Counter;
        level : INT;
    END_VAR
    c(pulse := TRUE);
    level := c.count;
END_PROGRAM
";

#[test]
fn a_session_with_diagnostics_completion_definition_and_errors() {
    let mut c = Client::start();
    let init = c.request(
        "initialize",
        json!({"processId": null, "rootUri": null, "capabilities": {}}),
    );
    assert!(
        init["result"]["capabilities"]["completionProvider"].is_object(),
        "{init}"
    );
    c.notify("initialized", json!({}));

    c.notify(
        "textDocument/didOpen",
        json!({"textDocument": {"uri": URI, "languageId": "iecst", "version": 1, "text": TEXT}}),
    );
    assert_eq!(c.diagnostics(URI), Vec::<Value>::new());

    // A half-typed edit: the same code as `stc check` gives, at its place.
    let broken = TEXT.replace(
        "level := c.count;",
        "level := c.count + ;\n    level := TRUE;",
    );
    c.notify(
        "textDocument/didChange",
        json!({"textDocument": {"uri": URI, "version": 2}, "contentChanges": [{"text": broken}]}),
    );
    let d = c.diagnostics(URI);
    assert!(!d.is_empty(), "no diagnostics for a broken file");
    assert_eq!(d[0]["code"], "E0020", "{d:?}");
    assert_eq!(d[0]["range"]["start"]["line"], 23, "{d:?}");
    assert_eq!(d[0]["source"], "stc");

    // Back to the valid text for the requests: cleared, published once,
    // and the next edit's diagnostics are its own.
    c.notify(
        "textDocument/didChange",
        json!({"textDocument": {"uri": URI, "version": 3}, "contentChanges": [{"text": TEXT}]}),
    );
    assert_eq!(c.diagnostics(URI), Vec::<Value>::new());
    c.notify(
        "textDocument/didChange",
        json!({"textDocument": {"uri": URI, "version": 4}, "contentChanges": [{"text": broken}]}),
    );
    assert!(!c.diagnostics(URI).is_empty());
    c.notify(
        "textDocument/didChange",
        json!({"textDocument": {"uri": URI, "version": 5}, "contentChanges": [{"text": TEXT}]}),
    );
    assert_eq!(c.diagnostics(URI), Vec::<Value>::new());

    // Members after `.`: the FB's inputs and outputs.
    let r = c.request("textDocument/completion", pos(23, 15));
    let labels: Vec<&str> = r["result"]
        .as_array()
        .expect("completion list")
        .iter()
        .map(|i| i["label"].as_str().unwrap())
        .collect();
    assert!(
        labels.contains(&"count") && labels.contains(&"pulse"),
        "{labels:?}"
    );
    assert!(!labels.contains(&"level"), "{labels:?}");

    // Names in scope and keywords elsewhere.
    let r = c.request("textDocument/completion", pos(23, 4));
    let labels: Vec<&str> = r["result"]
        .as_array()
        .unwrap()
        .iter()
        .map(|i| i["label"].as_str().unwrap())
        .collect();
    for want in ["level", "c", "Counter", "Main", "Auto", "IF", "INT"] {
        assert!(labels.contains(&want), "{want} missing: {labels:?}");
    }

    // Go to definition: a variable, a member, a type.
    let r = c.request("textDocument/definition", pos(23, 5));
    assert_eq!(r["result"]["uri"], URI, "{r}");
    assert_eq!(
        r["result"]["range"]["start"],
        json!({"line": 20, "character": 8})
    );
    let r = c.request("textDocument/definition", pos(23, 16));
    assert_eq!(
        r["result"]["range"]["start"],
        json!({"line": 10, "character": 8}),
        "{r}"
    );
    let r = c.request("textDocument/definition", pos(19, 13));
    assert_eq!(
        r["result"]["range"]["start"],
        json!({"line": 5, "character": 15}),
        "{r}"
    );

    // Hover: the declaration and its comment.
    let r = c.request("textDocument/hover", pos(23, 16));
    let v = r["result"]["contents"]["value"].as_str().unwrap();
    assert!(
        v.contains("(VAR_OUTPUT) count : INT") && v.contains("edges so far"),
        "{v}"
    );
    let r = c.request("textDocument/hover", pos(19, 13));
    let v = r["result"]["contents"]["value"].as_str().unwrap();
    assert!(
        v.contains("FUNCTION_BLOCK Counter") && v.contains("Counts rising edges."),
        "{v}"
    );

    // Document symbols.
    let r = c.request(
        "textDocument/documentSymbol",
        json!({"textDocument": {"uri": URI}}),
    );
    let names: Vec<&str> = r["result"]
        .as_array()
        .unwrap()
        .iter()
        .map(|s| s["name"].as_str().unwrap())
        .collect();
    assert_eq!(names, ["Mode", "Counter", "Main"]);

    // Formatting through stc fmt.
    let r = c.request(
        "textDocument/formatting",
        json!({"textDocument": {"uri": URI}, "options": {"tabSize": 4, "insertSpaces": true}}),
    );
    assert_eq!(r["result"], json!([]), "already formatted: {r}");

    // A position outside the file is an error, and the server lives on.
    let r = c.request("textDocument/definition", pos(500, 0));
    assert_eq!(r["error"]["code"], -32602, "{r}");
    let r = c.request("textDocument/completion", pos(0, 99));
    assert_eq!(r["error"]["code"], -32602, "{r}");

    let r = c.request("shutdown", Value::Null);
    assert!(r.get("error").is_none(), "{r}");
    c.notify("exit", Value::Null);
    let status = c.child.wait().unwrap();
    assert!(status.success(), "{status:?}");
}

/// The latency of diagnostics after an edit in a 100 000-line project
/// (docs/benchmarks.md): `cargo test --release -p stc --test lsp --
/// --ignored --nocapture`.
#[test]
#[ignore]
fn diagnostics_latency_on_a_100k_line_project() {
    let big = stc_bench::generate(100_000);
    if let Ok(p) = std::env::var("STC_LSP_BENCH_DUMP") {
        std::fs::write(p, &big).unwrap();
    }
    let lines = big.lines().count();
    let mut c = Client::start();
    c.request(
        "initialize",
        json!({"processId": null, "rootUri": null, "capabilities": {}}),
    );
    c.notify("initialized", json!({}));
    let big_uri = "file:///virtual/big.st";
    c.notify(
        "textDocument/didOpen",
        json!({"textDocument": {"uri": big_uri, "languageId": "iecst", "version": 1, "text": big}}),
    );
    let big_diags = c.diagnostics(big_uri);
    assert!(
        big_diags.is_empty(),
        "{:?}",
        &big_diags[..big_diags.len().min(3)]
    );
    let small =
        "PROGRAM Edited\n    VAR\n        x : INT;\n    END_VAR\n    x := x + 1;\nEND_PROGRAM\n";
    c.notify(
        "textDocument/didOpen",
        json!({"textDocument": {"uri": URI, "languageId": "iecst", "version": 1, "text": small}}),
    );
    let _ = c.diagnostics(URI);
    let mut times = Vec::new();
    for i in 0..7 {
        let text = if i % 2 == 0 {
            small.replace("x + 1", "'text'")
        } else {
            small.to_string()
        };
        let t = std::time::Instant::now();
        c.notify(
            "textDocument/didChange",
            json!({"textDocument": {"uri": URI, "version": i + 2}, "contentChanges": [{"text": text}]}),
        );
        let d = c.diagnostics(URI);
        times.push(t.elapsed().as_secs_f64() * 1000.0);
        assert_eq!(d.is_empty(), i % 2 == 1, "{d:?} {:?}", c.notifications);
    }
    times.sort_by(|a, b| a.partial_cmp(b).unwrap());
    println!(
        "project of {} lines: diagnostics after an edit in ms: min {:.0}, median {:.0}, max {:.0}",
        lines + small.lines().count(),
        times[0],
        times[times.len() / 2],
        times[times.len() - 1]
    );
    c.request("shutdown", Value::Null);
    c.notify("exit", Value::Null);
    let _ = c.child.wait();
}
