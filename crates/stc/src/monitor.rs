//! Online monitoring and forcing (`stc run --realtime --monitor
//! HOST:PORT`): an HTTP API, a WebSocket stream and a web page, served
//! with axum on a thread of its own (docs/runtime.md, "The monitor").
//!
//! The server never touches the program's memory. Everything it asks of
//! the program goes through [`Shared`], under one lock, and is done by
//! [`Monitor`] between two cycles: forces are written before a cycle
//! (after the inputs) and again after it (before the outputs); reads are
//! answered after a cycle, from the memory as that cycle left it. Paths
//! are resolved with the runtime's `Scope`, values read from ST literals
//! and printed as `--format json` prints them (`stc_runtime::monitor`).
//!
//! Every request that changes something (force, unforce) needs the token,
//! `Authorization: Bearer TOKEN`: 401 without it, 403 with another one.
//! A malformed request is an error for that request only (JSON
//! `{"error": "..."}` with a 4xx status); a body is at most 64 KiB.

use std::net::SocketAddr;
use std::sync::{Arc, Mutex, MutexGuard};
use std::time::{Duration, Instant};

use axum::body::Bytes;
use axum::extract::rejection::{BytesRejection, QueryRejection};
use axum::extract::ws::{Message, WebSocket, WebSocketUpgrade};
use axum::extract::{DefaultBodyLimit, Query, State};
use axum::http::{header, HeaderMap, HeaderValue, StatusCode};
use axum::response::{IntoResponse, Response};
use axum::routing::{get, post};
use axum::Router;
use stc_ir::model::{Model, ProgramInst};
use stc_runtime::monitor::{json_of, variables, Forces, VarInfo};
use stc_runtime::path::{split_list, Place, Scope};
use stc_runtime::report::json_string;
use stc_runtime::timing::Stats;
use stc_runtime::{Between, Simulation};
use stc_syntax::literal::format_duration;
use tokio::sync::{mpsc, oneshot};

/// The web page: one file, no build step.
const PAGE: &str = include_str!("monitor_page.html");

/// The largest request body.
const MAX_BODY: usize = 64 * 1024;
/// The most variables the list holds.
const MAX_VARIABLES: usize = 10_000;
/// How long a read waits for the end of a cycle.
const READ_TIMEOUT: Duration = Duration::from_secs(5);
/// The default and smallest time between two WebSocket messages.
const DEFAULT_EVERY: Duration = Duration::from_millis(50);
/// WebSocket streams at once; more are refused (503).
const MAX_STREAMS: usize = 64;

/// A WebSocket subscriber.
struct Sub {
    id: u64,
    places: Vec<Place>,
    tx: mpsc::Sender<String>,
    every: Duration,
    last: Option<Instant>,
}

/// What the server and the cycle share.
#[derive(Default)]
pub struct Shared {
    forces: Forces,
    /// Reads waiting for the end of a cycle.
    queries: Vec<(Vec<Place>, oneshot::Sender<String>)>,
    subs: Vec<Sub>,
    next_sub: u64,
    /// The run has ended (the reads will not be answered).
    ended: bool,
}

fn lock(m: &Mutex<Shared>) -> MutexGuard<'_, Shared> {
    // Every change under the lock is a plain store or a push: a panic
    // elsewhere left it consistent.
    m.lock().unwrap_or_else(|e| e.into_inner())
}

/// The values of `places` after cycle `cycle`, as one JSON object.
fn snapshot(
    model: &Model,
    sim: &Simulation,
    places: &[Place],
    forces: &Forces,
    time_ns: i64,
) -> String {
    let mut out = format!(
        "{{\"cycle\":{},\"time\":{},\"values\":{{",
        sim.completed(),
        json_string(&format_duration(time_ns, false))
    );
    for (i, p) in places.iter().enumerate() {
        if i > 0 {
            out.push(',');
        }
        out.push_str(&json_string(&p.name));
        out.push(':');
        out.push_str(&json_of(model, sim.engine(), p));
    }
    out.push_str("},\"forced\":[");
    for (i, f) in forces.0.iter().enumerate() {
        if i > 0 {
            out.push(',');
        }
        out.push_str(&json_string(&f.place.name));
    }
    out.push_str("]}");
    out
}

/// The monitor's part of the cycle: see the module documentation.
pub struct Monitor {
    shared: Arc<Mutex<Shared>>,
    model: Arc<Model>,
}

impl Between for Monitor {
    fn before_cycle(&mut self, sim: &mut Simulation, _k: u64) {
        let g = lock(&self.shared);
        if !g.forces.0.is_empty() {
            g.forces.apply(&self.model, sim.engine_mut());
        }
    }

    fn after_cycle(&mut self, sim: &mut Simulation, k: u64) {
        let mut g = lock(&self.shared);
        if !g.forces.0.is_empty() {
            g.forces.apply(&self.model, sim.engine_mut());
        }
        if g.queries.is_empty() && g.subs.is_empty() {
            return;
        }
        let time_ns = sim.plan().time_of(k).unwrap_or(i64::MAX);
        let g = &mut *g;
        for (places, reply) in g.queries.drain(..) {
            let _ = reply.send(snapshot(&self.model, sim, &places, &g.forces, time_ns));
        }
        let now = Instant::now();
        g.subs.retain_mut(|s| {
            if s.tx.is_closed() {
                return false;
            }
            if s.last.is_some_and(|l| now.duration_since(l) < s.every) {
                return true;
            }
            // A subscriber that has not taken the last message skips
            // this one: a slow reader never holds the cycle.
            if s.tx
                .try_send(snapshot(&self.model, sim, &s.places, &g.forces, time_ns))
                .is_ok()
            {
                s.last = Some(now);
            }
            true
        });
    }

    fn at_end(&mut self, _sim: &mut Simulation) {
        lock(&self.shared).ended = true;
    }

    fn faulted(&mut self, _sim: &mut Simulation, _k: u64, _f: &stc_vm::VmFault) {
        lock(&self.shared).ended = true;
    }
}

/// What the request handlers know.
struct Server {
    model: Arc<Model>,
    instances: Vec<ProgramInst>,
    config: Option<u32>,
    vars: Vec<VarInfo>,
    token: String,
    shared: Arc<Mutex<Shared>>,
    stats: Arc<Mutex<Stats>>,
    /// `/api/info` (fixed).
    info: String,
}

impl Server {
    fn scope(&self) -> Scope<'_> {
        Scope {
            model: &self.model,
            instances: &self.instances,
            config: self.config,
        }
    }

    fn shared(&self) -> MutexGuard<'_, Shared> {
        lock(&self.shared)
    }
}

type S = State<Arc<Server>>;

fn json(status: StatusCode, body: String) -> Response {
    (
        status,
        [
            (
                header::CONTENT_TYPE,
                HeaderValue::from_static("application/json"),
            ),
            (header::CACHE_CONTROL, HeaderValue::from_static("no-store")),
        ],
        body,
    )
        .into_response()
}

fn error(status: StatusCode, message: impl std::fmt::Display) -> Response {
    json(
        status,
        format!("{{\"error\":{}}}", json_string(&message.to_string())),
    )
}

/// A refused request: its status and message (small, unlike a
/// `Response`, to pass around in a `Result`).
struct Refusal(StatusCode, String);

fn refuse(status: StatusCode, message: impl std::fmt::Display) -> Refusal {
    Refusal(status, message.to_string())
}

impl IntoResponse for Refusal {
    fn into_response(self) -> Response {
        let mut r = error(self.0, self.1);
        if self.0 == StatusCode::UNAUTHORIZED {
            r.headers_mut()
                .insert(header::WWW_AUTHENTICATE, HeaderValue::from_static("Bearer"));
        }
        r
    }
}

/// The status of a runtime error about a path or a value.
fn status_of(e: &stc_runtime::Error) -> StatusCode {
    match e {
        stc_runtime::Error::Path(_) => StatusCode::NOT_FOUND,
        _ => StatusCode::UNPROCESSABLE_ENTITY,
    }
}

/// Checks the token of a request that changes something.
fn authorize(s: &Server, headers: &HeaderMap) -> Result<(), Refusal> {
    let Some(value) = headers.get(header::AUTHORIZATION) else {
        return Err(refuse(
            StatusCode::UNAUTHORIZED,
            "forcing needs the monitor's token: send `Authorization: Bearer TOKEN` (the token is printed at start, or given with --monitor-token)",
        ));
    };
    let given = value
        .to_str()
        .ok()
        .and_then(|v| v.strip_prefix("Bearer "))
        .map(str::trim)
        .unwrap_or("");
    // Compared in time independent of where they differ.
    let (a, b) = (given.as_bytes(), s.token.as_bytes());
    let mut diff = a.len() ^ b.len();
    for (i, y) in b.iter().enumerate() {
        diff |= usize::from(a.get(i).copied().unwrap_or(0) ^ y);
    }
    if diff != 0 {
        return Err(refuse(StatusCode::FORBIDDEN, "wrong token"));
    }
    Ok(())
}

/// The body of a request as a JSON object.
fn body_object(
    body: Result<Bytes, BytesRejection>,
) -> Result<serde_json::Map<String, serde_json::Value>, Refusal> {
    let bytes = body.map_err(|e| {
        let status = e.status();
        if status == StatusCode::PAYLOAD_TOO_LARGE {
            refuse(
                status,
                format!("the request body is larger than {MAX_BODY} bytes"),
            )
        } else {
            refuse(status, e.body_text())
        }
    })?;
    match serde_json::from_slice::<serde_json::Value>(&bytes) {
        Ok(serde_json::Value::Object(m)) => Ok(m),
        Ok(_) => Err(refuse(
            StatusCode::BAD_REQUEST,
            "the body must be a JSON object such as {\"path\": \"Main.x\", \"value\": \"42\"}",
        )),
        Err(e) => Err(refuse(
            StatusCode::BAD_REQUEST,
            format!("the body is not JSON: {e}"),
        )),
    }
}

fn field_path(m: &serde_json::Map<String, serde_json::Value>) -> Result<String, Refusal> {
    match m.get("path") {
        Some(serde_json::Value::String(p)) => Ok(p.clone()),
        Some(_) => Err(refuse(
            StatusCode::BAD_REQUEST,
            "`path` must be a string (a variable path such as Main.x)",
        )),
        None => Err(refuse(StatusCode::BAD_REQUEST, "`path` is missing")),
    }
}

async fn page() -> Response {
    (
        [
            (
                header::CONTENT_TYPE,
                HeaderValue::from_static("text/html; charset=utf-8"),
            ),
            (header::CACHE_CONTROL, HeaderValue::from_static("no-store")),
        ],
        PAGE,
    )
        .into_response()
}

async fn info_handler(State(s): S) -> Response {
    json(StatusCode::OK, s.info.clone())
}

async fn list(State(s): S) -> Response {
    let forced: Vec<String> = s
        .shared()
        .forces
        .0
        .iter()
        .map(|f| f.place.name.clone())
        .collect();
    let mut out = String::from("{\"variables\":[");
    for (i, v) in s.vars.iter().enumerate() {
        if i > 0 {
            out.push(',');
        }
        out.push_str(&format!(
            "{{\"path\":{},\"type\":{},\"forcible\":{},\"forced\":{}}}",
            json_string(&v.path),
            json_string(&v.ty),
            v.forcible,
            forced.contains(&v.path)
        ));
    }
    out.push_str("]}");
    json(StatusCode::OK, out)
}

/// The places a `paths` parameter names (every listed variable without
/// it).
fn places(s: &Server, paths: Option<&String>) -> Result<Vec<Place>, Refusal> {
    let scope = s.scope();
    let mut out: Vec<Place> = Vec::new();
    let list: Vec<String> = match paths {
        Some(p) => split_list(p),
        None => s
            .vars
            .iter()
            .filter(|v| v.forcible || !v.ty.starts_with("ARRAY"))
            .map(|v| v.path.clone())
            .collect(),
    };
    if list.len() > MAX_VARIABLES {
        return Err(refuse(
            StatusCode::BAD_REQUEST,
            format!("at most {MAX_VARIABLES} paths at once"),
        ));
    }
    for p in list {
        let place = scope.resolve(&p).map_err(|e| refuse(status_of(&e), e))?;
        if !out.iter().any(|q| q.name == place.name) {
            out.push(place);
        }
    }
    Ok(out)
}

type Params = Result<Query<std::collections::HashMap<String, String>>, QueryRejection>;

fn params(q: Params) -> Result<std::collections::HashMap<String, String>, Refusal> {
    q.map(|Query(m)| m)
        .map_err(|e| refuse(StatusCode::BAD_REQUEST, e.body_text()))
}

async fn values(State(s): S, q: Params) -> Response {
    let q = match params(q) {
        Ok(q) => q,
        Err(r) => return r.into_response(),
    };
    let places = match places(&s, q.get("paths")) {
        Ok(p) => p,
        Err(r) => return r.into_response(),
    };
    let (tx, rx) = oneshot::channel();
    {
        let mut g = s.shared();
        if g.ended {
            return error(StatusCode::SERVICE_UNAVAILABLE, "the program has stopped");
        }
        g.queries.push((places, tx));
    }
    match tokio::time::timeout(READ_TIMEOUT, rx).await {
        Ok(Ok(body)) => json(StatusCode::OK, body),
        _ => error(
            StatusCode::SERVICE_UNAVAILABLE,
            "no cycle ended within 5 s: the program is not running",
        ),
    }
}

async fn stats_handler(State(s): S) -> Response {
    let body = s.stats.lock().unwrap_or_else(|e| e.into_inner()).to_json();
    json(StatusCode::OK, body)
}

fn forces_json(f: &Forces) -> String {
    let mut out = String::from("{\"forces\":[");
    for (i, f) in f.0.iter().enumerate() {
        if i > 0 {
            out.push(',');
        }
        out.push_str(&format!(
            "{{\"path\":{},\"value\":{}}}",
            json_string(&f.place.name),
            json_string(&f.text)
        ));
    }
    out.push_str("]}");
    out
}

async fn forces(State(s): S) -> Response {
    let body = forces_json(&s.shared().forces);
    json(StatusCode::OK, body)
}

async fn force(State(s): S, headers: HeaderMap, body: Result<Bytes, BytesRejection>) -> Response {
    if let Err(r) = authorize(&s, &headers) {
        return r.into_response();
    }
    let m = match body_object(body) {
        Ok(m) => m,
        Err(r) => return r.into_response(),
    };
    let path = match field_path(&m) {
        Ok(p) => p,
        Err(r) => return r.into_response(),
    };
    // An ST literal as text; JSON booleans and numbers are taken as the
    // literal they print as.
    let text = match m.get("value") {
        Some(serde_json::Value::String(t)) => t.clone(),
        Some(serde_json::Value::Bool(b)) => if *b { "TRUE" } else { "FALSE" }.to_string(),
        Some(serde_json::Value::Number(n)) => n.to_string(),
        Some(_) => {
            return error(
                StatusCode::BAD_REQUEST,
                "`value` must be an ST literal as a string (\"42\", \"TRUE\", \"T#1s\"), a number or a boolean",
            )
        }
        None => return error(StatusCode::BAD_REQUEST, "`value` is missing"),
    };
    let scope = s.scope();
    let mut g = s.shared();
    match g.forces.force(&scope, &path, &text) {
        Ok(name) => json(
            StatusCode::OK,
            format!(
                "{{\"forced\":{},\"value\":{}}}",
                json_string(&name),
                json_string(text.trim())
            ),
        ),
        Err(e) => error(status_of(&e), e),
    }
}

async fn unforce(State(s): S, headers: HeaderMap, body: Result<Bytes, BytesRejection>) -> Response {
    if let Err(r) = authorize(&s, &headers) {
        return r.into_response();
    }
    let m = match body_object(body) {
        Ok(m) => m,
        Err(r) => return r.into_response(),
    };
    if m.get("all") == Some(&serde_json::Value::Bool(true)) {
        let n = std::mem::take(&mut s.shared().forces.0).len();
        return json(StatusCode::OK, format!("{{\"released\":{n}}}"));
    }
    let path = match field_path(&m) {
        Ok(p) => p,
        Err(r) => return r.into_response(),
    };
    let scope = s.scope();
    let released = s.shared().forces.release(&scope, &path);
    match released {
        Ok(true) => json(
            StatusCode::OK,
            format!(
                "{{\"released\":1,\"path\":{}}}",
                json_string(&scope.resolve(&path).map(|p| p.name).unwrap_or(path))
            ),
        ),
        Ok(false) => error(StatusCode::CONFLICT, format!("`{path}` is not forced")),
        Err(e) => error(status_of(&e), e),
    }
}

/// Reads a duration parameter: `100ms`, `T#1s`, or `0` (every cycle).
fn every(q: Option<&String>) -> Result<Duration, Refusal> {
    match q.map(|t| t.trim()) {
        None => Ok(DEFAULT_EVERY),
        Some("0") => Ok(Duration::ZERO),
        Some(t) => stc_runtime::parse_tick(t)
            .map(|ns| Duration::from_nanos(ns as u64))
            .map_err(|_| {
                refuse(
                    StatusCode::BAD_REQUEST,
                    format!(
                        "interval `{t}`: expected a duration such as 100ms, or 0 for every cycle"
                    ),
                )
            }),
    }
}

async fn ws(
    State(s): S,
    q: Params,
    upgrade: Result<WebSocketUpgrade, axum::extract::ws::rejection::WebSocketUpgradeRejection>,
) -> Response {
    let q = match params(q) {
        Ok(q) => q,
        Err(r) => return r.into_response(),
    };
    let upgrade = match upgrade {
        Ok(u) => u,
        Err(e) => {
            return error(
                e.status(),
                format!("{}: connect with a WebSocket client", e.body_text()),
            )
        }
    };
    let places = match places(&s, q.get("paths")) {
        Ok(p) => p,
        Err(r) => return r.into_response(),
    };
    let every = match every(q.get("interval")) {
        Ok(e) => e,
        Err(r) => return r.into_response(),
    };
    let (tx, rx) = mpsc::channel(2);
    let id = {
        let mut g = s.shared();
        if g.subs.len() >= MAX_STREAMS {
            return error(
                StatusCode::SERVICE_UNAVAILABLE,
                format!("at most {MAX_STREAMS} streams at once"),
            );
        }
        g.next_sub += 1;
        let id = g.next_sub;
        g.subs.push(Sub {
            id,
            places,
            tx,
            every,
            last: None,
        });
        id
    };
    upgrade
        .max_message_size(MAX_BODY)
        .max_frame_size(MAX_BODY)
        .on_failed_upgrade(move |_| {})
        .on_upgrade(move |socket| stream(s, socket, rx, id))
}

/// One WebSocket: pushes the values; takes `{"watch": [paths]}` to change
/// them (`{"error": ...}` answers a message it cannot use).
async fn stream(s: Arc<Server>, mut socket: WebSocket, mut rx: mpsc::Receiver<String>, id: u64) {
    loop {
        tokio::select! {
            msg = rx.recv() => {
                let Some(text) = msg else { break };
                if socket.send(Message::Text(text.into())).await.is_err() {
                    break;
                }
            }
            incoming = socket.recv() => {
                let text = match incoming {
                    Some(Ok(Message::Text(t))) => t.to_string(),
                    Some(Ok(Message::Binary(_))) => {
                        let e = "{\"error\":\"send text: {\\\"watch\\\": [\\\"Main.x\\\", ...]}\"}";
                        if socket.send(Message::Text(e.into())).await.is_err() {
                            break;
                        }
                        continue;
                    }
                    Some(Ok(Message::Close(_))) | None | Some(Err(_)) => break,
                    Some(Ok(_)) => continue,
                };
                let answer = match watch_message(&s, &text) {
                    Ok(places) => {
                        if let Some(sub) = s.shared().subs.iter_mut().find(|x| x.id == id) {
                            sub.places = places;
                        }
                        continue;
                    }
                    Err(e) => format!("{{\"error\":{}}}", json_string(&e)),
                };
                if socket.send(Message::Text(answer.into())).await.is_err() {
                    break;
                }
            }
        }
    }
    s.shared().subs.retain(|x| x.id != id);
}

fn watch_message(s: &Server, text: &str) -> Result<Vec<Place>, String> {
    let v: serde_json::Value = serde_json::from_str(text).map_err(|e| format!("not JSON: {e}"))?;
    let list = v
        .get("watch")
        .and_then(|w| w.as_array())
        .ok_or("expected {\"watch\": [\"Main.x\", ...]}")?;
    let scope = s.scope();
    let mut out: Vec<Place> = Vec::new();
    for p in list {
        let p = p.as_str().ok_or("a path is a string")?;
        let place = scope.resolve(p).map_err(|e| e.to_string())?;
        if !out.iter().any(|q| q.name == place.name) {
            out.push(place);
        }
    }
    Ok(out)
}

/// A token: 128 random bits in hex.
pub fn new_token() -> String {
    let mut bytes = [0u8; 16];
    let from_os = std::fs::File::open("/dev/urandom")
        .and_then(|mut f| std::io::Read::read_exact(&mut f, &mut bytes))
        .is_ok();
    if !from_os {
        use std::hash::{BuildHasher, Hasher};
        for chunk in bytes.chunks_mut(8) {
            let mut h = std::collections::hash_map::RandomState::new().build_hasher();
            h.write_u128(
                std::time::SystemTime::now()
                    .duration_since(std::time::UNIX_EPOCH)
                    .map_or(0, |d| d.as_nanos()),
            );
            h.write_u32(std::process::id());
            chunk.copy_from_slice(&h.finish().to_le_bytes()[..chunk.len()]);
        }
    }
    bytes.iter().map(|b| format!("{b:02x}")).collect()
}

/// `HOST:PORT`, `:PORT` or `PORT`: the address to bind, loopback when no
/// host is given.
pub fn bind_address(text: &str) -> String {
    let t = text.trim();
    if t.parse::<u16>().is_ok() {
        format!("127.0.0.1:{t}")
    } else if let Some(port) = t.strip_prefix(':') {
        format!("127.0.0.1:{port}")
    } else {
        t.to_string()
    }
}

/// Starts the monitor of `sim` on `addr` with `token`; returns the part
/// to run between cycles and the bound address. An error is the caller's
/// exit 2.
pub fn start(
    sim: &Simulation,
    addr: &str,
    token: String,
    stats: Arc<Mutex<Stats>>,
) -> Result<(Monitor, SocketAddr), String> {
    let bind = bind_address(addr);
    let listener = std::net::TcpListener::bind(&bind)
        .map_err(|e| format!("--monitor {addr}: cannot listen: {e}"))?;
    let bound = listener
        .local_addr()
        .map_err(|e| format!("--monitor {addr}: {e}"))?;
    listener
        .set_nonblocking(true)
        .map_err(|e| format!("--monitor {addr}: {e}"))?;
    let shared = Arc::new(Mutex::new(Shared::default()));
    let plan = sim.plan();
    let what = match (plan.config, &plan.chosen) {
        (Some(c), _) => sim
            .model()
            .configs
            .get(c as usize)
            .map_or(String::new(), |c| c.name.clone()),
        _ => plan
            .instances
            .first()
            .map_or(String::new(), |i| i.name.clone()),
    };
    let tasks: Vec<String> = plan.tasks.iter().map(|t| json_string(&t.name)).collect();
    let info = format!(
        "{{\"running\":{},\"tick\":{},\"tick_ns\":{},\"tasks\":[{}],\"engine\":{}}}",
        json_string(&what),
        json_string(&format_duration(plan.tick_ns, false)),
        plan.tick_ns,
        tasks.join(","),
        json_string(sim.engine().name())
    );
    let server = Arc::new(Server {
        model: Arc::clone(sim.model()),
        instances: plan.instances.clone(),
        config: plan.config,
        vars: variables(&sim.scope(), MAX_VARIABLES),
        token,
        shared: Arc::clone(&shared),
        stats,
        info,
    });
    let app = Router::new()
        .route("/", get(page))
        .route("/api/info", get(info_handler))
        .route("/api/variables", get(list))
        .route("/api/values", get(values))
        .route("/api/stats", get(stats_handler))
        .route("/api/forces", get(forces))
        .route("/api/force", post(force))
        .route("/api/unforce", post(unforce))
        .route("/api/ws", get(ws))
        .fallback(|| async {
            error(
                StatusCode::NOT_FOUND,
                "no such endpoint: see docs/runtime.md",
            )
        })
        .layer(DefaultBodyLimit::max(MAX_BODY))
        .with_state(server);
    let rt = tokio::runtime::Builder::new_multi_thread()
        .worker_threads(1)
        .enable_io()
        .enable_time()
        .build()
        .map_err(|e| format!("--monitor {addr}: cannot start the server: {e}"))?;
    std::thread::Builder::new()
        .name("monitor".into())
        .spawn(move || {
            rt.block_on(async move {
                let Ok(listener) = tokio::net::TcpListener::from_std(listener) else {
                    return;
                };
                // `serve` returns only if accepting fails for good; then
                // the monitor is gone but the controller goes on.
                let _ = axum::serve(listener, app).await;
            });
        })
        .map_err(|e| format!("--monitor {addr}: cannot start the server: {e}"))?;
    Ok((
        Monitor {
            shared,
            model: Arc::clone(sim.model()),
        },
        bound,
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn addresses_without_a_host_bind_loopback() {
        assert_eq!(bind_address("8080"), "127.0.0.1:8080");
        assert_eq!(bind_address(":0"), "127.0.0.1:0");
        assert_eq!(bind_address("0.0.0.0:80"), "0.0.0.0:80");
    }

    #[test]
    fn tokens_are_128_bits_of_hex() {
        let (a, b) = (new_token(), new_token());
        assert_eq!(a.len(), 32);
        assert!(a.bytes().all(|c| c.is_ascii_hexdigit()));
        assert_ne!(a, b);
    }
}
