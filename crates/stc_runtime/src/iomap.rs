//! The hardware allocation map and the process image of the controller
//! (`stc run --realtime --io-map FILE --modbus HOST:PORT`).
//!
//! The map (TOML, read by [`IoMap::parse`]) binds variables to I/O
//! channels without changing the compiled program: `[[modbus]]` entries
//! bind a variable to a Modbus server table and address, `[[sim]]` entries
//! drive an input from a simulated signal (for tests and demonstrations).
//! The Modbus layout ([`Layout`]) is OpenPLC's default layout of the
//! located variables (docs/cli.md) plus the map's entries; an address used
//! twice, a type that does not fit its table, an unknown variable or an
//! unknown key is an error naming the map's line, before anything runs.
//!
//! [`ProcessImage`] holds the Modbus tables between cycles. Clients read
//! and write it at any time (under the caller's lock); what they write is
//! marked and copied into the program's memory only by
//! [`ProcessImage::apply`], before a cycle, all at once; the program's
//! values are copied out by [`ProcessImage::refresh`] after a cycle, except
//! where a client's write is still pending. So the program never sees a
//! half-written image and a write is never lost to a refresh. Nothing here
//! does I/O: the `stc` crate runs the server.

use serde::Deserialize;
use stc_ir::layout::elem_size;
use stc_ir::model::Model;
use stc_syntax::literal::{AddrArea, AddrSize};
use stc_syntax::token::ElemType;
use stc_values::{convert, Value};
use toml::Spanned;

use crate::engine::{write_value, Memory};
use crate::error::{Error, Result};
use crate::path::{Loc, Place, Scope, View};
use crate::sim::{Between, Simulation};

/// A Modbus data table.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum Table {
    /// Read/write bits (function codes 1, 5, 15).
    Coil,
    /// Read-only bits (function code 2).
    Discrete,
    /// Read-only registers (function code 4).
    Input,
    /// Read/write registers (function codes 3, 6, 16).
    Holding,
}

impl Table {
    const ALL: [Table; 4] = [Table::Coil, Table::Discrete, Table::Input, Table::Holding];

    fn index(self) -> usize {
        self as usize
    }

    fn parse(s: &str) -> Option<Table> {
        Some(match s {
            "coil" => Table::Coil,
            "discrete" => Table::Discrete,
            "input" => Table::Input,
            "holding" => Table::Holding,
            _ => return None,
        })
    }

    fn is_bits(self) -> bool {
        matches!(self, Table::Coil | Table::Discrete)
    }

    /// Whether clients write it.
    pub fn is_written(self) -> bool {
        matches!(self, Table::Coil | Table::Holding)
    }

    fn noun(self) -> &'static str {
        match self {
            Table::Coil => "coil",
            Table::Discrete => "discrete input",
            Table::Input => "input register",
            Table::Holding => "holding register",
        }
    }
}

/// One variable in a Modbus table: `count` bits or registers from
/// `address` (registers high word first).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Entry {
    pub name: String,
    pub table: Table,
    pub address: u16,
    pub count: u16,
    pub elem: ElemType,
    pub loc: Loc,
    /// The map's line, or `None` for the default layout.
    pub line: Option<usize>,
}

/// A simulated signal.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Wave {
    /// Always `low`.
    Constant,
    /// From `low` up to `high` over a period, then again.
    Ramp,
    /// `low` for the first half of a period, `high` for the second.
    Square,
}

/// An input driven by a simulated signal before every cycle.
#[derive(Clone, Debug, PartialEq)]
pub struct SimChannel {
    pub place: Place,
    pub elem: ElemType,
    pub wave: Wave,
    pub low: f64,
    pub high: f64,
    pub period_ns: i64,
}

impl SimChannel {
    /// The signal at task time `t_ns`.
    pub fn value_at(&self, t_ns: i64) -> f64 {
        let phase = if self.period_ns > 0 {
            (t_ns.rem_euclid(self.period_ns)) as f64 / self.period_ns as f64
        } else {
            0.0
        };
        match self.wave {
            Wave::Constant => self.low,
            Wave::Ramp => self.low + (self.high - self.low) * phase,
            Wave::Square if phase < 0.5 => self.low,
            Wave::Square => self.high,
        }
    }

    /// Writes the signal at `t_ns` into memory.
    pub fn drive(&self, model: &Model, mem: &mut dyn Memory, t_ns: i64) -> bool {
        let View::Type(ty) = self.place.view else {
            return false;
        };
        let Some(addr) = self.place.loc.address(mem) else {
            return false;
        };
        let x = self.value_at(t_ns);
        let v = if self.elem == ElemType::Bool {
            Value::Bool(x >= 0.5)
        } else {
            match convert(
                ElemType::Lreal,
                self.elem,
                &Value::Real(x.round_ties_even_if_int(self.elem)),
            ) {
                Ok(v) => v,
                Err(_) => return false,
            }
        };
        write_value(mem, model, addr, ty, &v)
    }
}

trait RoundForInt {
    fn round_ties_even_if_int(self, e: ElemType) -> f64;
}

impl RoundForInt for f64 {
    fn round_ties_even_if_int(self, e: ElemType) -> f64 {
        if matches!(e, ElemType::Real | ElemType::Lreal) {
            self
        } else {
            self.round_ties_even()
        }
    }
}

/// The allocation map, resolved against what runs.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct IoMap {
    pub modbus: Vec<Entry>,
    pub sim: Vec<SimChannel>,
    pub clients: Vec<ClientChannel>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct MapFile {
    #[serde(default)]
    modbus: Vec<Spanned<ModbusEntry>>,
    #[serde(default)]
    sim: Vec<Spanned<SimEntry>>,
    #[serde(default)]
    client: Vec<Spanned<ClientEntry>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct ClientEntry {
    device: Spanned<String>,
    #[serde(default = "unit_one")]
    unit: Spanned<i64>,
    table: Spanned<String>,
    address: Spanned<i64>,
    count: Option<Spanned<i64>>,
    variables: Spanned<Vec<Spanned<String>>>,
    #[serde(default)]
    write: bool,
    poll: Option<Spanned<String>>,
}

fn unit_one() -> Spanned<i64> {
    Spanned::new(0..0, 1)
}

/// The poll period of a client channel without `poll`.
pub const DEFAULT_POLL_NS: i64 = 100_000_000;

/// A block of a remote Modbus TCP server's table, polled by the
/// controller and bound to variables (`[[client]]` in the map).
#[derive(Clone, Debug, PartialEq)]
pub struct ClientChannel {
    /// `host:port` of the remote server.
    pub device: String,
    pub unit: u8,
    pub table: Table,
    pub address: u16,
    /// Bits or registers, all the variables' together.
    pub count: u16,
    /// Written to the device (coils and holding registers only) rather
    /// than read from it.
    pub write: bool,
    pub poll_ns: i64,
    /// The variables in order: each with its first bit or register in the
    /// block and how many it takes.
    pub vars: Vec<(Place, ElemType, u16, u16)>,
    /// The map's line.
    pub line: usize,
}

/// What one request moves: bits or registers.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum ClientData {
    Bits(Vec<bool>),
    Regs(Vec<u16>),
}

impl ClientChannel {
    /// A short name for messages: `modbus client DEVICE (holding 0..3)`.
    pub fn describe(&self) -> String {
        format!(
            "modbus client {} unit {} ({} {}..{})",
            self.device,
            self.unit,
            self.table.noun(),
            self.address,
            u32::from(self.address) + u32::from(self.count) - 1
        )
    }

    /// Writes what a poll read into the variables.
    pub fn load(&self, model: &Model, mem: &mut dyn Memory, data: &ClientData) {
        for (place, elem, at, n) in &self.vars {
            let (at, n) = (*at as usize, *n as usize);
            let Some(addr) = place.loc.address(mem) else {
                continue;
            };
            match data {
                ClientData::Bits(bits) => {
                    if let Some(&b) = bits.get(at) {
                        if let View::Type(ty) = place.view {
                            write_value(mem, model, addr, ty, &Value::Bool(b));
                        }
                    }
                }
                ClientData::Regs(regs) => {
                    let (Some(regs), Some(bytes)) =
                        (regs.get(at..at + n), mem.bytes_mut(addr, elem_size(*elem)))
                    else {
                        continue;
                    };
                    regs_to_bytes(regs, bytes);
                }
            }
        }
    }

    /// The variables' values, to write to the device.
    pub fn store(&self, mem: &dyn Memory) -> ClientData {
        if self.table.is_bits() {
            let mut bits = vec![false; self.count as usize];
            for (place, elem, at, _) in &self.vars {
                if let Some(b) = place
                    .loc
                    .address(mem)
                    .and_then(|a| mem.bytes(a, elem_size(*elem)))
                {
                    bits[*at as usize] = b[0] & 1 != 0;
                }
            }
            ClientData::Bits(bits)
        } else {
            let mut regs = vec![0u16; self.count as usize];
            for (place, elem, at, n) in &self.vars {
                if let Some(b) = place
                    .loc
                    .address(mem)
                    .and_then(|a| mem.bytes(a, elem_size(*elem)))
                {
                    let (at, n) = (*at as usize, *n as usize);
                    bytes_to_regs(b, &mut regs[at..at + n]);
                }
            }
            ClientData::Regs(regs)
        }
    }
}

/// What a client channel and its poller share: the last poll's data not
/// yet given to the program, and the program's last values to write.
#[derive(Debug, Default)]
pub struct ClientBuffer {
    pub input: Option<ClientData>,
    pub output: Option<ClientData>,
}

/// The client channels of a map between cycles: before a cycle, the data
/// every read channel's last complete poll brought (each channel's block
/// as one request read it); after one, the values of the written
/// channels' variables for their pollers. Only the buffers' locks are
/// taken, for a copy: the cycle never waits for the network.
pub struct Clients(
    pub  Vec<(
        ClientChannel,
        std::sync::Arc<std::sync::Mutex<ClientBuffer>>,
    )>,
);

impl Between for Clients {
    fn before_cycle(&mut self, sim: &mut Simulation, _k: u64) {
        let model = std::sync::Arc::clone(sim.model());
        // Take every fresh block first, then write them all.
        let fresh: Vec<Option<ClientData>> = self
            .0
            .iter()
            .map(|(ch, buf)| {
                if ch.write {
                    None
                } else {
                    buf.lock().unwrap_or_else(|e| e.into_inner()).input.take()
                }
            })
            .collect();
        for ((ch, _), data) in self.0.iter().zip(fresh) {
            if let Some(d) = data {
                ch.load(&model, sim.engine_mut(), &d);
            }
        }
    }

    fn after_cycle(&mut self, sim: &mut Simulation, _k: u64) {
        for (ch, buf) in &self.0 {
            if ch.write {
                let data = ch.store(sim.engine());
                buf.lock().unwrap_or_else(|e| e.into_inner()).output = Some(data);
            }
        }
    }
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct ModbusEntry {
    variable: Spanned<String>,
    table: Spanned<String>,
    address: Spanned<i64>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct SimEntry {
    variable: Spanned<String>,
    wave: Spanned<String>,
    #[serde(default)]
    low: f64,
    #[serde(default = "one")]
    high: f64,
    period: Option<Spanned<String>>,
}

fn one() -> f64 {
    1.0
}

/// The 1-based line of a byte offset.
fn line_of(text: &str, at: usize) -> usize {
    text.as_bytes()[..at.min(text.len())]
        .iter()
        .filter(|&&b| b == b'\n')
        .count()
        + 1
}

/// How many registers a value of `e` takes; `None` for what no register
/// holds.
fn registers(e: ElemType) -> Option<u16> {
    if matches!(
        e,
        ElemType::Bool | ElemType::String | ElemType::Wstring | ElemType::Char | ElemType::Wchar
    ) {
        return None;
    }
    Some(match elem_size(e) {
        1 | 2 => 1,
        4 => 2,
        8 => 4,
        _ => return None,
    })
}

impl IoMap {
    /// Reads a map and resolves it against `scope`; errors name `file`
    /// and the line.
    pub fn parse(file: &str, text: &str, scope: &Scope) -> Result<IoMap> {
        let err = |at: usize, message: String| Error::Map {
            file: file.to_string(),
            line: line_of(text, at),
            message,
        };
        let raw: MapFile = toml::from_str(text).map_err(|e| {
            err(
                e.span().map_or(0, |s| s.start),
                e.message().trim().to_string(),
            )
        })?;
        let model = scope.model;
        let resolve = |v: &Spanned<String>, writes: bool| -> Result<(Place, ElemType)> {
            let at = v.span().start;
            let place = scope
                .resolve(v.get_ref())
                .map_err(|e| err(at, e.to_string()))?;
            let elem = match &place.view {
                View::Type(t) => model.scalar_of(*t),
                View::Slice { .. } => None,
            }
            .ok_or_else(|| {
                let what = match &place.view {
                    View::Type(t) => match model.types.get(*t as usize) {
                        Some(stc_ir::model::TypeDesc::String { wide: false, .. }) => {
                            "a STRING: no channel holds text"
                        }
                        Some(stc_ir::model::TypeDesc::String { wide: true, .. }) => {
                            "a WSTRING: no channel holds text"
                        }
                        _ => "not an elementary variable: bind its elements one by one",
                    },
                    View::Slice { .. } => {
                        "not an elementary variable: bind its elements one by one"
                    }
                };
                err(at, format!("`{}` is {what}", place.name))
            })?;
            if writes && place.constant {
                return Err(err(at, format!("`{}` is a constant", place.name)));
            }
            Ok((place, elem))
        };
        let mut map = IoMap::default();
        for e in &raw.modbus {
            let e = e.get_ref();
            let table = Table::parse(e.table.get_ref()).ok_or_else(|| {
                err(
                    e.table.span().start,
                    format!(
                        "unknown table `{}`: expected coil, discrete, input or holding",
                        e.table.get_ref()
                    ),
                )
            })?;
            let (place, elem) = resolve(&e.variable, table.is_written())?;
            let at = e.variable.span().start;
            let count = if table.is_bits() {
                if elem != ElemType::Bool {
                    return Err(err(
                        at,
                        format!(
                            "`{}` is {}: a {} holds a BOOL",
                            place.name,
                            elem.name(),
                            table.noun()
                        ),
                    ));
                }
                1
            } else {
                registers(elem).ok_or_else(|| {
                    err(
                        at,
                        format!(
                            "`{}` is {}: a {} holds a number or a bit string (BOOL goes to a coil or a discrete input)",
                            place.name,
                            elem.name(),
                            table.noun()
                        ),
                    )
                })?
            };
            let address = *e.address.get_ref();
            if address < 0 || address + i64::from(count) > 65536 {
                return Err(err(
                    e.address.span().start,
                    format!(
                        "address {address}: a {} address is 0 to 65535 ({} needs {count})",
                        table.noun(),
                        place.name
                    ),
                ));
            }
            map.modbus.push(Entry {
                name: place.name.clone(),
                table,
                address: address as u16,
                count,
                elem,
                loc: place.loc,
                line: Some(line_of(text, e.address.span().start)),
            });
        }
        for s in &raw.sim {
            let s = s.get_ref();
            let wave = match s.wave.get_ref().as_str() {
                "constant" => Wave::Constant,
                "ramp" => Wave::Ramp,
                "square" => Wave::Square,
                w => {
                    return Err(err(
                        s.wave.span().start,
                        format!("unknown wave `{w}`: expected constant, ramp or square"),
                    ))
                }
            };
            let (place, elem) = resolve(&s.variable, true)?;
            if registers(elem).is_none() && elem != ElemType::Bool {
                return Err(err(
                    s.variable.span().start,
                    format!(
                        "`{}` is {}: a simulated signal is a number or a BOOL",
                        place.name,
                        elem.name()
                    ),
                ));
            }
            let period_ns = match &s.period {
                Some(p) => crate::parse_tick(p.get_ref()).map_err(|_| {
                    err(
                        p.span().start,
                        format!("period `{}`: expected a duration such as 10s", p.get_ref()),
                    )
                })?,
                None if wave == Wave::Constant => 0,
                None => {
                    return Err(err(
                        s.wave.span().start,
                        "a ramp or square wave needs a `period`".into(),
                    ))
                }
            };
            map.sim.push(SimChannel {
                place,
                elem,
                wave,
                low: s.low,
                high: s.high,
                period_ns,
            });
        }
        for c in &raw.client {
            let c = c.get_ref();
            let table = Table::parse(c.table.get_ref()).ok_or_else(|| {
                err(
                    c.table.span().start,
                    format!(
                        "unknown table `{}`: expected coil, discrete, input or holding",
                        c.table.get_ref()
                    ),
                )
            })?;
            if c.write && !table.is_written() {
                return Err(err(
                    c.table.span().start,
                    format!(
                        "`write = true` needs a coil or holding register: a device's {}s are read only",
                        table.noun()
                    ),
                ));
            }
            let device = c.device.get_ref().trim().to_string();
            let port_ok = device
                .rsplit_once(':')
                .is_some_and(|(h, p)| !h.is_empty() && p.parse::<u16>().is_ok());
            if !port_ok {
                return Err(err(
                    c.device.span().start,
                    format!("device `{device}`: expected HOST:PORT, such as 192.168.0.10:502"),
                ));
            }
            let unit = *c.unit.get_ref();
            let unit = u8::try_from(unit).map_err(|_| {
                err(
                    c.unit.span().start,
                    format!("unit {unit}: a unit id is 0 to 255"),
                )
            })?;
            if c.variables.get_ref().is_empty() {
                return Err(err(
                    c.variables.span().start,
                    "`variables` is empty: bind at least one variable".into(),
                ));
            }
            let mut vars = Vec::new();
            let mut at: u16 = 0;
            for v in c.variables.get_ref() {
                let (place, elem) = resolve(v, !c.write)?;
                let n = if table.is_bits() {
                    if elem != ElemType::Bool {
                        return Err(err(
                            v.span().start,
                            format!(
                                "`{}` is {}: a {} holds a BOOL",
                                place.name,
                                elem.name(),
                                table.noun()
                            ),
                        ));
                    }
                    1
                } else {
                    registers(elem).ok_or_else(|| {
                        err(
                            v.span().start,
                            format!(
                                "`{}` is {}: a {} holds a number or a bit string",
                                place.name,
                                elem.name(),
                                table.noun()
                            ),
                        )
                    })?
                };
                vars.push((place, elem, at, n));
                at = at.saturating_add(n);
            }
            let count = at;
            if let Some(n) = &c.count {
                if *n.get_ref() != i64::from(count) {
                    return Err(err(
                        n.span().start,
                        format!(
                            "count {}: the variables take {count} {}",
                            n.get_ref(),
                            if table.is_bits() { "bits" } else { "registers" }
                        ),
                    ));
                }
            }
            let max = match (table.is_bits(), c.write) {
                (true, false) => MAX_BITS,
                (true, true) => 1968,
                (false, false) => MAX_REGS,
                (false, true) => 123,
            };
            if count > max {
                return Err(err(
                    c.variables.span().start,
                    format!(
                        "the variables take {count} {}: one request moves at most {max}",
                        if table.is_bits() { "bits" } else { "registers" }
                    ),
                ));
            }
            let address = *c.address.get_ref();
            if address < 0 || address + i64::from(count) > 65536 {
                return Err(err(
                    c.address.span().start,
                    format!(
                        "address {address}: a {} address is 0 to 65535 (the block takes {count})",
                        table.noun()
                    ),
                ));
            }
            let poll_ns = match &c.poll {
                Some(p) => crate::parse_tick(p.get_ref()).map_err(|_| {
                    err(
                        p.span().start,
                        format!("poll `{}`: expected a duration such as 100ms", p.get_ref()),
                    )
                })?,
                None => DEFAULT_POLL_NS,
            };
            map.clients.push(ClientChannel {
                device,
                unit,
                table,
                address: address as u16,
                count,
                write: c.write,
                poll_ns,
                vars,
                line: line_of(text, c.device.span().start),
            });
        }
        // The default layout first, so a clash names the map's line.
        let mut all = default_layout(model);
        all.append(&mut map.modbus);
        let mut by_table: Vec<&Entry> = all.iter().collect();
        by_table.sort_by_key(|e| (e.table, e.address));
        for w in by_table.windows(2) {
            let (a, b) = (w[0], w[1]);
            if a.table == b.table
                && u32::from(a.address) + u32::from(a.count) > u32::from(b.address)
            {
                let (first, second) = if a.line.is_some() && b.line.is_none() {
                    (b, a)
                } else {
                    (a, b)
                };
                let line = second.line.or(first.line).unwrap_or(1);
                let where_ = first
                    .line
                    .map_or("the default layout".to_string(), |l| format!("line {l}"));
                return Err(Error::Map {
                    file: file.to_string(),
                    line,
                    message: format!(
                        "{} {} is used twice: by `{}` here and by `{}` ({where_})",
                        b.table.noun(),
                        b.address,
                        second.name,
                        first.name
                    ),
                });
            }
        }
        map.modbus = all;
        Ok(map)
    }
}

/// OpenPLC's default layout of the located variables (docs/cli.md): coils
/// = `%QX` (byte * 8 + bit), discrete inputs = `%IX`, input registers =
/// `%IW`, holding registers 0..1023 = `%QW`, 1024.. = `%MW`, 2048.. =
/// `%MD` (two each), 4096.. = `%ML` (four each). Other located variables
/// have no Modbus address.
pub fn default_layout(model: &Model) -> Vec<Entry> {
    let mut out = Vec::new();
    for slot in &model.io {
        let a = &slot.address;
        let Some(elem) = model.scalar_of(slot.ty) else {
            continue;
        };
        let n = |i: usize| a.path.get(i).copied().map(u64::from);
        let place = match (a.area, a.size, a.path.len()) {
            (AddrArea::Output, AddrSize::Bit, 2) => {
                (Table::Coil, n(0).zip(n(1)).map(|(b, x)| b * 8 + x), 1)
            }
            (AddrArea::Input, AddrSize::Bit, 2) => {
                (Table::Discrete, n(0).zip(n(1)).map(|(b, x)| b * 8 + x), 1)
            }
            (AddrArea::Input, AddrSize::Word, 1) => (Table::Input, n(0), 1),
            (AddrArea::Output, AddrSize::Word, 1) => {
                (Table::Holding, n(0).filter(|&w| w < 1024), 1)
            }
            (AddrArea::Memory, AddrSize::Word, 1) => (
                Table::Holding,
                n(0).map(|w| 1024 + w).filter(|&w| w < 2048),
                1,
            ),
            (AddrArea::Memory, AddrSize::Dword, 1) => (
                Table::Holding,
                n(0).map(|w| 2048 + 2 * w).filter(|&w| w < 4096),
                2,
            ),
            (AddrArea::Memory, AddrSize::Lword, 1) => {
                (Table::Holding, n(0).map(|w| 4096 + 4 * w), 4)
            }
            _ => continue,
        };
        let (table, Some(address), count) = place else {
            continue;
        };
        if address + count > 65536 {
            continue;
        }
        let fits = if table.is_bits() {
            elem == ElemType::Bool
        } else {
            registers(elem).is_some_and(|r| r <= count as u16)
        };
        if !fits {
            continue;
        }
        out.push(Entry {
            name: a.to_string(),
            table,
            address: address as u16,
            count: count as u16,
            elem,
            loc: Loc::at(slot.offset),
            line: None,
        });
    }
    out
}

/// A Modbus exception a request gets.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Exception {
    IllegalDataAddress,
    IllegalDataValue,
}

/// The Modbus tables between cycles: see the module documentation.
pub struct ProcessImage {
    entries: Vec<Entry>,
    bits: [Vec<bool>; 2],
    regs: [Vec<u16>; 2],
    /// Per entry: written by a client since the last [`ProcessImage::apply`].
    dirty: Vec<bool>,
    /// Per table: for each address, the entry there (`u32::MAX`: none).
    owner: [Vec<u32>; 4],
}

/// The most bits or registers one request may read (the protocol's own
/// limits: 2000 bits, 125 registers).
pub const MAX_BITS: u16 = 2000;
pub const MAX_REGS: u16 = 125;

impl ProcessImage {
    pub fn new(entries: Vec<Entry>) -> ProcessImage {
        let mut size = [0usize; 4];
        for e in &entries {
            let end = e.address as usize + e.count as usize;
            size[e.table.index()] = size[e.table.index()].max(end);
        }
        let mut owner: [Vec<u32>; 4] = Default::default();
        for t in Table::ALL {
            owner[t.index()] = vec![u32::MAX; size[t.index()]];
        }
        for (i, e) in entries.iter().enumerate() {
            let (a, n) = (e.address as usize, e.count as usize);
            owner[e.table.index()][a..a + n].fill(i as u32);
        }
        ProcessImage {
            dirty: vec![false; entries.len()],
            bits: [vec![false; size[0]], vec![false; size[1]]],
            regs: [vec![0; size[2]], vec![0; size[3]]],
            entries,
            owner,
        }
    }

    pub fn entries(&self) -> &[Entry] {
        &self.entries
    }

    fn range(
        &self,
        t: Table,
        addr: u16,
        n: u16,
        max: u16,
    ) -> Result<std::ops::Range<usize>, Exception> {
        if n == 0 || n > max {
            return Err(Exception::IllegalDataValue);
        }
        let (a, end) = (addr as usize, addr as usize + n as usize);
        if end > self.owner[t.index()].len() {
            return Err(Exception::IllegalDataAddress);
        }
        Ok(a..end)
    }

    /// Reads coils or discrete inputs.
    pub fn read_bits(&self, t: Table, addr: u16, n: u16) -> Result<Vec<bool>, Exception> {
        let r = self.range(t, addr, n, MAX_BITS)?;
        let i = if t == Table::Coil { 0 } else { 1 };
        Ok(self.bits[i][r].to_vec())
    }

    /// Reads input or holding registers.
    pub fn read_regs(&self, t: Table, addr: u16, n: u16) -> Result<Vec<u16>, Exception> {
        let r = self.range(t, addr, n, MAX_REGS)?;
        let i = if t == Table::Input { 0 } else { 1 };
        Ok(self.regs[i][r].to_vec())
    }

    /// Writes coils (a client's request; applied before the next cycle).
    pub fn write_coils(&mut self, addr: u16, values: &[bool]) -> Result<(), Exception> {
        let r = self.range(Table::Coil, addr, values.len() as u16, 1968)?;
        for (a, v) in r.zip(values) {
            self.bits[0][a] = *v;
            self.mark(Table::Coil, a);
        }
        Ok(())
    }

    /// Writes holding registers (applied before the next cycle).
    pub fn write_regs(&mut self, addr: u16, values: &[u16]) -> Result<(), Exception> {
        let r = self.range(Table::Holding, addr, values.len() as u16, 123)?;
        for (a, v) in r.zip(values) {
            self.regs[1][a] = *v;
            self.mark(Table::Holding, a);
        }
        Ok(())
    }

    fn mark(&mut self, t: Table, a: usize) {
        if let Some(&o) = self.owner[t.index()].get(a) {
            if let Some(d) = self.dirty.get_mut(o as usize) {
                *d = true;
            }
        }
    }

    /// Before a cycle: the clients' writes into memory, all at once.
    pub fn apply(&mut self, mem: &mut dyn Memory) {
        for (i, e) in self.entries.iter().enumerate() {
            if !std::mem::take(&mut self.dirty[i]) {
                continue;
            }
            let Some(addr) = e.loc.address(mem) else {
                continue;
            };
            let size = elem_size(e.elem);
            let Some(bytes) = mem.bytes_mut(addr, size) else {
                continue;
            };
            let a = e.address as usize;
            match e.table {
                Table::Coil => bytes[0] = self.bits[0][a] as u8,
                Table::Holding => {
                    let regs = &self.regs[1][a..a + e.count as usize];
                    regs_to_bytes(regs, bytes);
                }
                _ => {}
            }
        }
    }

    /// After a cycle: the program's values into the tables, but for
    /// clients' writes not applied yet.
    pub fn refresh(&mut self, mem: &dyn Memory) {
        for (i, e) in self.entries.iter().enumerate() {
            if self.dirty[i] {
                continue;
            }
            let Some(addr) = e.loc.address(mem) else {
                continue;
            };
            let Some(bytes) = mem.bytes(addr, elem_size(e.elem)) else {
                continue;
            };
            let a = e.address as usize;
            match e.table {
                Table::Coil | Table::Discrete => {
                    self.bits[e.table.index()][a] = bytes[0] & 1 != 0;
                }
                Table::Input | Table::Holding => {
                    let t = e.table.index() - 2;
                    bytes_to_regs(bytes, &mut self.regs[t][a..a + e.count as usize]);
                }
            }
        }
    }
}

/// A little-endian value into registers, high word first (a one-byte
/// value in one register, zero- or sign-extended as it reads back).
fn bytes_to_regs(bytes: &[u8], regs: &mut [u16]) {
    if bytes.len() == 1 {
        if let Some(r) = regs.first_mut() {
            *r = u16::from(bytes[0]);
        }
        return;
    }
    let n = regs.len();
    for (i, r) in regs.iter_mut().enumerate() {
        let w = n - 1 - i;
        *r = u16::from_le_bytes([bytes[2 * w], bytes[2 * w + 1]]);
    }
}

/// Registers, high word first, into a little-endian value (a one-byte
/// value takes the register's low byte).
fn regs_to_bytes(regs: &[u16], bytes: &mut [u8]) {
    if bytes.len() == 1 {
        bytes[0] = regs.first().map_or(0, |r| *r as u8);
        return;
    }
    let n = regs.len();
    for (i, r) in regs.iter().enumerate() {
        let w = n - 1 - i;
        let [lo, hi] = r.to_le_bytes();
        bytes[2 * w] = lo;
        bytes[2 * w + 1] = hi;
    }
}

/// The simulated channels of a map, driven before every cycle at the
/// cycle's task time.
pub struct SimInputs(pub Vec<SimChannel>);

impl Between for SimInputs {
    fn before_cycle(&mut self, sim: &mut Simulation, k: u64) {
        let t = sim.plan().time_of(k).unwrap_or(i64::MAX);
        let model = std::sync::Arc::clone(sim.model());
        for ch in &self.0 {
            ch.drive(&model, sim.engine_mut(), t);
        }
    }
}

/// The process image shared with a Modbus server: clients' writes go into
/// memory before each cycle, the program's values come out after it.
pub struct Exchange(pub std::sync::Arc<std::sync::Mutex<ProcessImage>>);

impl Exchange {
    fn image(&self) -> std::sync::MutexGuard<'_, ProcessImage> {
        // A server thread that panicked while holding the lock left the
        // tables consistent (every write is a plain store): go on.
        self.0.lock().unwrap_or_else(|e| e.into_inner())
    }
}

impl Between for Exchange {
    fn before_cycle(&mut self, sim: &mut Simulation, _k: u64) {
        self.image().apply(sim.engine_mut());
    }
    fn after_cycle(&mut self, sim: &mut Simulation, _k: u64) {
        self.image().refresh(sim.engine());
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::schedule::{Chosen, Plan};
    use crate::testing::sample_model;

    fn parse(text: &str) -> Result<IoMap> {
        let m = sample_model();
        let plan = Plan::new(&m, Chosen::Config(0), None).unwrap();
        let scope = Scope {
            model: &m,
            instances: &plan.instances,
            config: plan.config,
        };
        IoMap::parse("map.toml", text, &scope)
    }

    fn error(text: &str) -> String {
        parse(text).unwrap_err().to_string()
    }

    #[test]
    fn entries_bind_variables_to_tables_beside_the_default_layout() {
        let map = parse(
            "# the map\n[[modbus]]\nvariable = \"main.flag\"\ntable = \"coil\"\naddress = 100\n\n\
             [[modbus]]\nvariable = \"g\"\ntable = \"holding\"\naddress = 7\n\n\
             [[sim]]\nvariable = \"main.x\"\nwave = \"ramp\"\nhigh = 10\nperiod = \"1s\"\n",
        )
        .unwrap();
        let flag = map.modbus.iter().find(|e| e.name == "main.flag").unwrap();
        assert_eq!(
            (flag.table, flag.address, flag.count, flag.line),
            (Table::Coil, 100, 1, Some(5))
        );
        let g = map.modbus.iter().find(|e| e.name == "g").unwrap();
        assert_eq!((g.table, g.count), (Table::Holding, 1));
        // %QX0.0 (the global lamp) is coil 0 by the default layout.
        assert!(map
            .modbus
            .iter()
            .any(|e| e.name == "%QX0.0" && e.table == Table::Coil && e.address == 0));
        assert_eq!(map.sim.len(), 1);
        assert_eq!(map.sim[0].value_at(500_000_000), 5.0);
    }

    #[test]
    fn mistakes_name_their_line() {
        let e = error("[[modbus]]\nvariable = \"main.nope\"\ntable = \"coil\"\naddress = 1\n");
        assert!(e.starts_with("map.toml:2: "), "{e}");
        let e = error("[[modbus]]\nvariable = \"main.count\"\ntable = \"coil\"\naddress = 1\n");
        assert!(
            e.starts_with("map.toml:2: ") && e.contains("INT: a coil holds a BOOL"),
            "{e}"
        );
        let e = error("[[modbus]]\nvariable = \"main.flag\"\ntable = \"holding\"\naddress = 1\n");
        assert!(e.contains("BOOL goes to a coil"), "{e}");
        let e = error("[[modbus]]\nvariable = \"main.name\"\ntable = \"input\"\naddress = 1\n");
        assert!(e.contains("STRING"), "{e}");
        let e = error("[[modbus]]\nvariable = \"main.flag\"\ntable = \"coils\"\naddress = 1\n");
        assert!(e.starts_with("map.toml:3: unknown table"), "{e}");
        let e = error("[[modbus]]\nvariable = \"main.flag\"\ntable = \"coil\"\naddress = 70000\n");
        assert!(e.starts_with("map.toml:4: address 70000"), "{e}");
        let e = error(
            "[[modbus]]\nvariable = \"main.flag\"\ntable = \"coil\"\naddress = 1\nunit = 3\n",
        );
        assert!(e.starts_with("map.toml:5: ") && e.contains("unit"), "{e}");
        let e = error("[[modbus]]\nvariable = \"K\"\ntable = \"holding\"\naddress = 1\n");
        assert!(e.contains("constant"), "{e}");
        let e = error("[output]\nx = 1\n");
        assert!(e.starts_with("map.toml:1: "), "{e}");
        let e = error("[[sim]]\nvariable = \"main.x\"\nwave = \"ramp\"\n");
        assert!(e.contains("needs a `period`"), "{e}");
    }

    #[test]
    fn client_channels_bind_variables_to_a_remote_block() {
        let map = parse(
            "[[client]]\ndevice = \"127.0.0.1:5020\"\ntable = \"holding\"\naddress = 3\n\
             variables = [\"main.count\", \"main.lx\"]\npoll = \"20ms\"\n\
             [[client]]\ndevice = \"plc:502\"\nunit = 7\ntable = \"coil\"\naddress = 0\n\
             variables = [\"main.flag\"]\nwrite = true\n",
        )
        .unwrap();
        let [a, b] = &map.clients[..] else {
            panic!("{:?}", map.clients)
        };
        assert_eq!(
            (a.unit, a.table, a.address, a.count, a.poll_ns, a.write),
            (1, Table::Holding, 3, 5, 20_000_000, false)
        );
        assert_eq!(
            (a.vars[0].2, a.vars[0].3, a.vars[1].2, a.vars[1].3),
            (0, 1, 1, 4)
        );
        assert_eq!(
            (b.unit, b.count, b.write, b.poll_ns),
            (7, 1, true, DEFAULT_POLL_NS)
        );
        // A round trip through the registers, high word first.
        let mut mem = crate::testing::sample().init;
        let m = sample_model();
        a.load(
            &m,
            &mut mem,
            &ClientData::Regs(vec![0xfffe, 0, 0, 0x1234, 0x5678]),
        );
        assert_eq!(
            a.store(&mem),
            ClientData::Regs(vec![0xfffe, 0, 0, 0x1234, 0x5678])
        );
        let e = |t: &str| error(&format!("[[client]]\ndevice = \"h:1\"\n{t}"));
        assert!(
            e("table = \"input\"\naddress = 0\nvariables = [\"main.count\"]\nwrite = true\n")
                .contains("read only")
        );
        assert!(
            e("table = \"coil\"\naddress = 0\nvariables = [\"main.count\"]\n")
                .contains("holds a BOOL")
        );
        assert!(
            e("table = \"input\"\naddress = 0\ncount = 2\nvariables = [\"main.count\"]\n")
                .starts_with("map.toml:5: count 2")
        );
        assert!(
            e("table = \"input\"\naddress = 65535\nvariables = [\"main.lx\"]\n")
                .contains("address 65535")
        );
        assert!(e("table = \"input\"\naddress = 0\nvariables = []\n").contains("empty"));
        assert!(e("table = \"input\"\naddress = 0\nvariables = [\"K\"]\n").contains("constant"));
        assert!(error("[[client]]\ndevice = \"nohost\"\ntable = \"input\"\naddress = 0\nvariables = [\"g\"]\n")
            .starts_with("map.toml:2: device `nohost`"));
    }

    #[test]
    fn an_address_used_twice_is_an_error_at_the_second_use() {
        let e = error(
            "[[modbus]]\nvariable = \"g\"\ntable = \"holding\"\naddress = 5\n\
             [[modbus]]\nvariable = \"main.count\"\ntable = \"holding\"\naddress = 5\n",
        );
        assert!(
            e.starts_with("map.toml:8: holding register 5 is used twice"),
            "{e}"
        );
        // Against the default layout: %QX0.0 is coil 0.
        let e = error("[[modbus]]\nvariable = \"main.flag\"\ntable = \"coil\"\naddress = 0\n");
        assert!(
            e.starts_with("map.toml:4: ") && e.contains("by `%QX0.0` (the default layout)"),
            "{e}"
        );
        // A register in the middle of a longer value.
        let e = error(
            "[[modbus]]\nvariable = \"main.lx\"\ntable = \"input\"\naddress = 10\n\
             [[modbus]]\nvariable = \"g\"\ntable = \"input\"\naddress = 13\n",
        );
        assert!(e.contains("input register 13 is used twice"), "{e}");
    }

    #[test]
    fn client_writes_reach_memory_only_when_applied_and_survive_a_refresh() {
        let entries = vec![
            Entry {
                name: "a".into(),
                table: Table::Holding,
                address: 0,
                count: 2,
                elem: ElemType::Dint,
                loc: Loc::at(0),
                line: None,
            },
            Entry {
                name: "b".into(),
                table: Table::Coil,
                address: 3,
                count: 1,
                elem: ElemType::Bool,
                loc: Loc::at(4),
                line: None,
            },
        ];
        let mut img = ProcessImage::new(entries);
        let mut mem = vec![0u8; 8];
        mem[..4].copy_from_slice(&0x0001_0002i32.to_le_bytes());
        img.refresh(&mem);
        assert_eq!(img.read_regs(Table::Holding, 0, 2), Ok(vec![1, 2]));
        img.write_regs(0, &[0x1234, 0x5678]).unwrap();
        img.write_coils(3, &[true]).unwrap();
        // The program's next values do not overwrite a pending write.
        mem[..4].copy_from_slice(&7i32.to_le_bytes());
        img.refresh(&mem);
        assert_eq!(
            img.read_regs(Table::Holding, 0, 2),
            Ok(vec![0x1234, 0x5678])
        );
        assert_eq!(mem[4], 0);
        img.apply(&mut mem);
        assert_eq!(
            i32::from_le_bytes(mem[..4].try_into().unwrap()),
            0x1234_5678
        );
        assert_eq!(mem[4], 1);
        // Illegal addresses and counts.
        assert_eq!(
            img.read_bits(Table::Coil, 3, 2),
            Err(Exception::IllegalDataAddress)
        );
        assert_eq!(
            img.read_regs(Table::Input, 0, 1),
            Err(Exception::IllegalDataAddress)
        );
        assert_eq!(
            img.read_regs(Table::Holding, 0, 0),
            Err(Exception::IllegalDataValue)
        );
        assert_eq!(
            img.write_regs(1, &[1, 2]),
            Err(Exception::IllegalDataAddress)
        );
    }
}
