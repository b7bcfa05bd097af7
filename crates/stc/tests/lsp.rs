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

const OTHER_URI: &str = "file:///virtual/other.st";

const OTHER: &str = "\
PROGRAM Other
    VAR
        k : Counter;
        n : INT;
    END_VAR
    k(pulse := n > 0);
    n := k.count;
END_PROGRAM
";

fn start_with_two_files() -> Client {
    let mut c = Client::start();
    c.request(
        "initialize",
        json!({"processId": null, "rootUri": null, "capabilities": {}}),
    );
    c.notify("initialized", json!({}));
    for (uri, text) in [(URI, TEXT), (OTHER_URI, OTHER)] {
        c.notify(
            "textDocument/didOpen",
            json!({"textDocument": {"uri": uri, "languageId": "iecst", "version": 1, "text": text}}),
        );
        assert_eq!(c.diagnostics(uri), Vec::<Value>::new(), "{uri}");
    }
    c
}

/// (uri, line, character) of each location, sorted.
fn places(r: &Value) -> Vec<(String, u64, u64)> {
    let mut out: Vec<(String, u64, u64)> = r["result"]
        .as_array()
        .unwrap_or_else(|| panic!("a list: {r}"))
        .iter()
        .map(|l| {
            (
                l["uri"].as_str().unwrap().to_string(),
                l["range"]["start"]["line"].as_u64().unwrap(),
                l["range"]["start"]["character"].as_u64().unwrap(),
            )
        })
        .collect();
    out.sort();
    out
}

#[test]
fn references_rename_semantic_tokens_and_signature_help() {
    let mut c = start_with_two_files();
    let init_caps = {
        // The capabilities are announced at initialize (checked here by a
        // second server, the first one's answer was consumed).
        let mut d = Client::start();
        let r = d.request(
            "initialize",
            json!({"processId": null, "rootUri": null, "capabilities": {}}),
        );
        d.notify("initialized", json!({}));
        d.request("shutdown", Value::Null);
        d.notify("exit", Value::Null);
        let _ = d.child.wait();
        r["result"]["capabilities"].clone()
    };
    assert_eq!(init_caps["referencesProvider"], true, "{init_caps}");
    assert_eq!(init_caps["renameProvider"]["prepareProvider"], true);
    assert!(init_caps["signatureHelpProvider"].is_object());
    let legend: Vec<String> = init_caps["semanticTokensProvider"]["legend"]["tokenTypes"]
        .as_array()
        .unwrap()
        .iter()
        .map(|t| t.as_str().unwrap().to_string())
        .collect();

    // References of an FB output: its declaration, the body, a member
    // access here and one in the other file.
    let refs = |c: &mut Client, uri: &str, line: u32, ch: u32, decl: bool| {
        c.request(
            "textDocument/references",
            json!({"textDocument": {"uri": uri}, "position": {"line": line, "character": ch},
                   "context": {"includeDeclaration": decl}}),
        )
    };
    let r = refs(&mut c, URI, 10, 9, true);
    let p = |u: &str, l: u64, ch: u64| (u.to_string(), l, ch);
    assert_eq!(
        places(&r),
        vec![
            p(OTHER_URI, 6, 11),
            p(URI, 10, 8),
            p(URI, 13, 8),
            p(URI, 13, 17),
            p(URI, 23, 15),
        ],
        "{r}"
    );
    // An input: also where a call names it (`pulse := ...`).
    let r = refs(&mut c, OTHER_URI, 5, 7, false);
    assert_eq!(
        places(&r),
        vec![p(OTHER_URI, 5, 6), p(URI, 12, 7), p(URI, 22, 6)],
        "{r}"
    );
    // A local variable stays in its POU.
    let r = refs(&mut c, URI, 23, 4, true);
    assert_eq!(places(&r), vec![p(URI, 20, 8), p(URI, 23, 4)], "{r}");

    // Rename across files.
    let r = c.request(
        "textDocument/rename",
        json!({"textDocument": {"uri": URI}, "position": {"line": 23, "character": 16}, "newName": "total"}),
    );
    let changes = &r["result"]["changes"];
    assert_eq!(changes[URI].as_array().map(Vec::len), Some(4), "{r}");
    assert_eq!(changes[OTHER_URI].as_array().map(Vec::len), Some(1), "{r}");
    assert!(changes[URI]
        .as_array()
        .unwrap()
        .iter()
        .all(|e| e["newText"] == "total"));
    // The FB type: its declaration and both instances' types.
    let r = c.request(
        "textDocument/rename",
        json!({"textDocument": {"uri": OTHER_URI}, "position": {"line": 2, "character": 12}, "newName": "EdgeCounter"}),
    );
    assert_eq!(
        r["result"]["changes"][URI].as_array().map(Vec::len),
        Some(2),
        "{r}"
    );
    assert_eq!(
        r["result"]["changes"][OTHER_URI].as_array().map(Vec::len),
        Some(1),
        "{r}"
    );
    let r = c.request(
        "textDocument/prepareRename",
        json!({"textDocument": {"uri": URI}, "position": {"line": 19, "character": 13}}),
    );
    assert_eq!(
        r["result"]["start"],
        json!({"line": 19, "character": 12}),
        "{r}"
    );
    // Refused: a keyword, an elementary type, a literal, a name clash, a
    // new name that is a keyword; an error for a position outside.
    for (line, ch, name) in [
        (12, 5, "x"),
        (10, 17, "x"),
        (22, 18, "x"),
        (20, 9, "c"),
        (20, 9, "END_IF"),
        (20, 9, "two words"),
    ] {
        let r = c.request(
            "textDocument/rename",
            json!({"textDocument": {"uri": URI}, "position": {"line": line, "character": ch}, "newName": name}),
        );
        assert_eq!(r["error"]["code"], -32803, "{line}:{ch} {name}: {r}");
    }
    let r = c.request(
        "textDocument/rename",
        json!({"textDocument": {"uri": URI}, "position": {"line": 99, "character": 0}, "newName": "x"}),
    );
    assert_eq!(r["error"]["code"], -32602, "{r}");
    let r = refs(&mut c, URI, 0, 400, true);
    assert_eq!(r["error"]["code"], -32602, "{r}");

    // Semantic tokens: decode and look at a few.
    let r = c.request(
        "textDocument/semanticTokens/full",
        json!({"textDocument": {"uri": URI}}),
    );
    let data: Vec<u64> = r["result"]["data"]
        .as_array()
        .unwrap_or_else(|| panic!("{r}"))
        .iter()
        .map(|v| v.as_u64().unwrap())
        .collect();
    assert_eq!(data.len() % 5, 0);
    let mut tokens = std::collections::BTreeMap::new();
    let (mut line, mut col) = (0u64, 0u64);
    for t in data.chunks(5) {
        if t[0] > 0 {
            line += t[0];
            col = t[1];
        } else {
            col += t[1];
        }
        tokens.insert((line, col), (legend[t[3] as usize].clone(), t[2], t[4]));
    }
    let kind = |l: u64, ch: u64| tokens.get(&(l, ch)).map(|t| t.0.as_str()).unwrap_or("none");
    assert_eq!(kind(4, 0), "comment");
    assert_eq!(kind(5, 0), "keyword");
    assert_eq!(kind(5, 15), "class");
    assert_eq!(kind(7, 8), "parameter");
    assert_eq!(tokens[&(7, 8)].2 & 1, 1, "a declaration");
    assert_eq!(kind(7, 16), "type");
    assert_eq!(kind(1, 12), "enumMember");
    assert_eq!(kind(13, 25), "number");
    assert_eq!(kind(20, 8), "variable");
    assert_eq!(kind(23, 15), "property");

    // Signature help in a call: the parameters, the one being written.
    let sig = |c: &mut Client, uri: &str, line: u32, ch: u32| {
        c.request(
            "textDocument/signatureHelp",
            json!({"textDocument": {"uri": uri}, "position": {"line": line, "character": ch}}),
        )
    };
    let r = sig(&mut c, URI, 22, 6);
    let s = &r["result"]["signatures"][0];
    assert_eq!(s["label"], "Counter(pulse := BOOL, count => INT)", "{r}");
    assert_eq!(s["documentation"], "Counts rising edges.", "{r}");
    assert_eq!(r["result"]["activeParameter"], 0, "{r}");
    let r = sig(&mut c, URI, 23, 10);
    assert_eq!(r["result"], Value::Null, "not in a call: {r}");
    // Half-typed: a call being written, the second argument started.
    let typing = TEXT.replace("    level := c.count;", "    c(pulse := TRUE, cou");
    c.notify(
        "textDocument/didChange",
        json!({"textDocument": {"uri": URI, "version": 2}, "contentChanges": [{"text": typing}]}),
    );
    assert!(!c.diagnostics(URI).is_empty());
    let r = sig(&mut c, URI, 23, 23);
    assert_eq!(r["result"]["activeParameter"], 1, "{r}");
    let r = c.request(
        "textDocument/semanticTokens/full",
        json!({"textDocument": {"uri": URI}}),
    );
    assert!(r["result"]["data"].is_array(), "{r}");
    let r = refs(&mut c, URI, 23, 5, true);
    assert!(r["result"].is_array(), "{r}");

    // Lints are diagnostics like the others (at their default levels).
    let linted = OTHER.replace(
        "n := k.count;",
        "n := k.count;\n    k(pulse := INT_TO_REAL(n) = 0.5);",
    );
    c.notify(
        "textDocument/didChange",
        json!({"textDocument": {"uri": OTHER_URI, "version": 2}, "contentChanges": [{"text": linted}]}),
    );
    let d = c.diagnostics(OTHER_URI);
    assert_eq!(d.len(), 1, "{d:?}");
    assert_eq!(d[0]["code"], "L0007", "{d:?}");
    assert_eq!(d[0]["severity"], 2, "a warning: {d:?}");

    c.request("shutdown", Value::Null);
    c.notify("exit", Value::Null);
    assert!(c.child.wait().unwrap().success());
}

/// Every prefix of a file (every 5th byte) is a half-typed file: each
/// request gets an answer (a result or an error), never a crash.
#[test]
fn half_typed_files_never_crash_a_request() {
    let mut c = start_with_two_files();
    let full = format!("{TEXT}{OTHER}");
    let mut version = 2;
    for end in (0..=full.len()).step_by(5) {
        let Some(text) = full.get(..end) else {
            continue;
        };
        version += 1;
        c.notify(
            "textDocument/didChange",
            json!({"textDocument": {"uri": URI, "version": version}, "contentChanges": [{"text": text}]}),
        );
        let _ = c.diagnostics(URI);
        let last_line = text.lines().count().saturating_sub(1) as u32;
        let last_col = text.lines().last().map_or(0, |l| l.len()) as u32;
        for (line, ch) in [(0, 0), (last_line, last_col), (last_line / 2, 4)] {
            let at =
                json!({"textDocument": {"uri": URI}, "position": {"line": line, "character": ch}});
            for method in [
                "textDocument/definition",
                "textDocument/hover",
                "textDocument/completion",
                "textDocument/signatureHelp",
                "textDocument/prepareRename",
            ] {
                let r = c.request(method, at.clone());
                assert!(
                    r.get("result").is_some() || r.get("error").is_some(),
                    "{method}: {r}"
                );
            }
            let mut refs = at.clone();
            refs["context"] = json!({"includeDeclaration": true});
            let r = c.request("textDocument/references", refs);
            assert!(r.get("result").is_some() || r.get("error").is_some(), "{r}");
            let mut rename = at.clone();
            rename["newName"] = json!("renamed");
            let r = c.request("textDocument/rename", rename);
            assert!(r.get("result").is_some() || r.get("error").is_some(), "{r}");
        }
        let r = c.request(
            "textDocument/semanticTokens/full",
            json!({"textDocument": {"uri": URI}}),
        );
        assert!(r["result"]["data"].is_array(), "{r}");
    }
    c.request("shutdown", Value::Null);
    c.notify("exit", Value::Null);
    assert!(c.child.wait().unwrap().success());
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
