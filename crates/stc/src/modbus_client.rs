//! The Modbus TCP client channels of the allocation map (`[[client]]`):
//! each channel polls a block of a remote server's table with
//! tokio-modbus, on a thread of its own, into the buffer it shares with
//! the cycle (`stc_runtime::iomap::Clients`), or writes the program's
//! values from it. The cycle only copies the buffers, so a slow, lost or
//! unreachable device never stalls it: the program keeps the last values
//! read until the device answers again.
//!
//! A lost connection (or one that cannot be made) is reported once on
//! stderr and retried every second; a reconnection is reported once too.
//! An exception answer (a block the device does not have, say) is
//! reported once and the channel goes on polling.

use std::sync::{Arc, Mutex};
use std::time::Duration;

use stc_runtime::iomap::{ClientBuffer, ClientChannel, ClientData, Clients, Table};
use tokio_modbus::client::{Context, Reader, Writer};
use tokio_modbus::Slave;

/// How long one request or connection attempt may take.
const TIMEOUT: Duration = Duration::from_secs(1);
/// Between two connection attempts.
const RETRY: Duration = Duration::from_secs(1);

type Warn = Arc<dyn Fn(String) + Send + Sync>;

/// Starts polling `channels`; returns what the cycle exchanges with them.
pub fn start(channels: Vec<ClientChannel>, warn: Warn) -> Result<Clients, String> {
    let rt = tokio::runtime::Builder::new_multi_thread()
        .worker_threads(1)
        .enable_io()
        .enable_time()
        .build()
        .map_err(|e| format!("cannot start the Modbus client channels: {e}"))?;
    let pairs: Vec<(ClientChannel, Arc<Mutex<ClientBuffer>>)> = channels
        .into_iter()
        .map(|c| (c, Arc::new(Mutex::new(ClientBuffer::default()))))
        .collect();
    let tasks: Vec<_> = pairs
        .iter()
        .map(|(c, b)| (c.clone(), Arc::clone(b), Arc::clone(&warn)))
        .collect();
    std::thread::Builder::new()
        .name("modbus-client".into())
        .spawn(move || {
            rt.block_on(async move {
                let mut set = tokio::task::JoinSet::new();
                for (c, b, w) in tasks {
                    set.spawn(poll(c, b, w));
                }
                while set.join_next().await.is_some() {}
            });
        })
        .map_err(|e| format!("cannot start the Modbus client channels: {e}"))?;
    Ok(Clients(pairs))
}

async fn connect(ch: &ClientChannel) -> Result<Context, String> {
    let mut last = format!("`{}` resolves to no address", ch.device);
    let addrs = tokio::time::timeout(TIMEOUT, tokio::net::lookup_host(ch.device.as_str()))
        .await
        .map_err(|_| "name lookup timed out".to_string())?
        .map_err(|e| e.to_string())?;
    for a in addrs {
        match tokio::time::timeout(
            TIMEOUT,
            tokio_modbus::client::tcp::connect_slave(a, Slave(ch.unit)),
        )
        .await
        {
            Ok(Ok(c)) => return Ok(c),
            Ok(Err(e)) => last = e.to_string(),
            Err(_) => last = "connection timed out".into(),
        }
    }
    Err(last)
}

/// One request: a read into the buffer, or a write from it.
async fn exchange(
    ch: &ClientChannel,
    c: &mut Context,
    buf: &Mutex<ClientBuffer>,
) -> Result<Result<(), tokio_modbus::ExceptionCode>, String> {
    let lock = || buf.lock().unwrap_or_else(|e| e.into_inner());
    let (a, n) = (ch.address, ch.count);
    let request = async {
        if ch.write {
            let out = lock().output.clone();
            return match out {
                Some(ClientData::Bits(b)) => c.write_multiple_coils(a, &b).await,
                Some(ClientData::Regs(r)) => c.write_multiple_registers(a, &r).await,
                // The program has not completed a cycle yet.
                None => Ok(Ok(())),
            };
        }
        let data = match ch.table {
            Table::Coil => c.read_coils(a, n).await.map(|r| r.map(ClientData::Bits)),
            Table::Discrete => c
                .read_discrete_inputs(a, n)
                .await
                .map(|r| r.map(ClientData::Bits)),
            Table::Input => c
                .read_input_registers(a, n)
                .await
                .map(|r| r.map(ClientData::Regs)),
            Table::Holding => c
                .read_holding_registers(a, n)
                .await
                .map(|r| r.map(ClientData::Regs)),
        };
        data.map(|r| {
            r.map(|mut d| {
                // A device that answers with more bits than asked for
                // (coils come in whole bytes) is cut to the block.
                if let ClientData::Bits(b) = &mut d {
                    b.truncate(n as usize);
                }
                lock().input = Some(d);
            })
        })
    };
    match tokio::time::timeout(TIMEOUT, request).await {
        Ok(Ok(r)) => Ok(r),
        Ok(Err(e)) => Err(e.to_string()),
        Err(_) => Err("no answer within 1 s".into()),
    }
}

async fn poll(ch: ClientChannel, buf: Arc<Mutex<ClientBuffer>>, warn: Warn) {
    let name = ch.describe();
    let period = Duration::from_nanos(ch.poll_ns.max(1) as u64);
    let mut ticker = tokio::time::interval(period);
    ticker.set_missed_tick_behavior(tokio::time::MissedTickBehavior::Delay);
    let mut ctx: Option<Context> = None;
    // Whether the loss of the device has been reported and not yet its
    // return; whether an exception has been reported.
    let (mut lost, mut excepted) = (false, false);
    let mut ever_connected = false;
    loop {
        ticker.tick().await;
        let c = match &mut ctx {
            Some(c) => c,
            None => match connect(&ch).await {
                Ok(c) => {
                    if lost {
                        warn(format!("note: {name}: connected again"));
                        lost = false;
                    }
                    ever_connected = true;
                    ctx.insert(c)
                }
                Err(e) => {
                    if !lost {
                        let what = if ever_connected {
                            "connection lost"
                        } else {
                            "cannot connect"
                        };
                        warn(format!(
                            "warning: {name}: {what}: {e}; retrying every second"
                        ));
                        lost = true;
                    }
                    tokio::time::sleep(RETRY).await;
                    continue;
                }
            },
        };
        match exchange(&ch, c, &buf).await {
            Ok(Ok(())) => excepted = false,
            Ok(Err(code)) => {
                if !excepted {
                    warn(format!("warning: {name}: the device answers {code:?}"));
                    excepted = true;
                }
            }
            Err(e) => {
                ctx = None;
                if !lost {
                    warn(format!(
                        "warning: {name}: connection lost: {e}; retrying every second"
                    ));
                    lost = true;
                }
            }
        }
    }
}
