//! The Modbus TCP server of the controller (`stc run --realtime --modbus
//! HOST:PORT`), with tokio-modbus for the protocol. It serves the process
//! image of `stc_runtime::iomap` (OpenPLC's layout plus the allocation
//! map) under its lock; the runtime copies clients' writes into the
//! program's memory between cycles, never during one.
//!
//! The server runs on its own thread with a one-worker tokio runtime; each
//! connection is a task, so a malformed frame, an oversized length or a
//! slow client ends or stalls only its own connection. Functions other
//! than 1-6, 15 and 16 get the exception "illegal function"; addresses
//! outside the tables "illegal data address"; counts outside the
//! protocol's limits "illegal data value".

use std::future;
use std::net::SocketAddr;
use std::sync::{Arc, Mutex, MutexGuard};

use stc_runtime::iomap::{Exception, ProcessImage, Table};
use tokio_modbus::server::tcp::{accept_tcp_connection, Server};
use tokio_modbus::{ExceptionCode, Request, Response};

struct Service {
    image: Arc<Mutex<ProcessImage>>,
}

fn code(e: Exception) -> ExceptionCode {
    match e {
        Exception::IllegalDataAddress => ExceptionCode::IllegalDataAddress,
        Exception::IllegalDataValue => ExceptionCode::IllegalDataValue,
    }
}

impl Service {
    fn image(&self) -> MutexGuard<'_, ProcessImage> {
        // Every write under the lock is a plain store: a panic elsewhere
        // left the tables consistent.
        self.image.lock().unwrap_or_else(|e| e.into_inner())
    }

    fn answer(&self, req: Request<'static>) -> Result<Response, ExceptionCode> {
        let mut img = self.image();
        Ok(match req {
            Request::ReadCoils(a, n) => {
                Response::ReadCoils(img.read_bits(Table::Coil, a, n).map_err(code)?)
            }
            Request::ReadDiscreteInputs(a, n) => {
                Response::ReadDiscreteInputs(img.read_bits(Table::Discrete, a, n).map_err(code)?)
            }
            Request::ReadInputRegisters(a, n) => {
                Response::ReadInputRegisters(img.read_regs(Table::Input, a, n).map_err(code)?)
            }
            Request::ReadHoldingRegisters(a, n) => {
                Response::ReadHoldingRegisters(img.read_regs(Table::Holding, a, n).map_err(code)?)
            }
            Request::WriteSingleCoil(a, v) => {
                img.write_coils(a, &[v]).map_err(code)?;
                Response::WriteSingleCoil(a, v)
            }
            Request::WriteMultipleCoils(a, vs) => {
                img.write_coils(a, &vs).map_err(code)?;
                Response::WriteMultipleCoils(a, vs.len() as u16)
            }
            Request::WriteSingleRegister(a, v) => {
                img.write_regs(a, &[v]).map_err(code)?;
                Response::WriteSingleRegister(a, v)
            }
            Request::WriteMultipleRegisters(a, vs) => {
                img.write_regs(a, &vs).map_err(code)?;
                Response::WriteMultipleRegisters(a, vs.len() as u16)
            }
            _ => return Err(ExceptionCode::IllegalFunction),
        })
    }
}

impl tokio_modbus::server::Service for Service {
    type Request = Request<'static>;
    type Response = Response;
    type Exception = ExceptionCode;
    type Future = future::Ready<Result<Response, ExceptionCode>>;

    fn call(&self, req: Self::Request) -> Self::Future {
        future::ready(self.answer(req))
    }
}

/// Binds `addr` (an error is the caller's exit 2) and serves `image` on a
/// thread of its own until the process ends; returns the bound address.
pub fn start(addr: &str, image: Arc<Mutex<ProcessImage>>) -> Result<SocketAddr, String> {
    let listener = std::net::TcpListener::bind(addr)
        .map_err(|e| format!("--modbus {addr}: cannot listen: {e}"))?;
    let bound = listener
        .local_addr()
        .map_err(|e| format!("--modbus {addr}: {e}"))?;
    listener
        .set_nonblocking(true)
        .map_err(|e| format!("--modbus {addr}: {e}"))?;
    let rt = tokio::runtime::Builder::new_multi_thread()
        .worker_threads(1)
        .enable_io()
        .enable_time()
        .build()
        .map_err(|e| format!("--modbus {addr}: cannot start the server: {e}"))?;
    std::thread::Builder::new()
        .name("modbus".into())
        .spawn(move || {
            rt.block_on(async move {
                let Ok(listener) = tokio::net::TcpListener::from_std(listener) else {
                    return;
                };
                let server = Server::new(listener);
                let new_service = |_peer: SocketAddr| {
                    Ok(Some(Service {
                        image: Arc::clone(&image),
                    }))
                };
                let on_connected = |stream, peer| {
                    let r = accept_tcp_connection(stream, peer, new_service);
                    async move { r }
                };
                // A broken connection is the client's business: it is
                // closed, the others go on. `serve` returns only when
                // accepting fails (out of file descriptors, say): wait a
                // moment and listen again rather than leave the controller
                // unreachable.
                loop {
                    let _ = server.serve(&on_connected, |_err| {}).await;
                    tokio::time::sleep(std::time::Duration::from_millis(100)).await;
                }
            });
        })
        .map_err(|e| format!("--modbus {addr}: cannot start the server: {e}"))?;
    Ok(bound)
}
