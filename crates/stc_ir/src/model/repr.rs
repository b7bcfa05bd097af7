//! How values are stored in memory, in every engine: BOOL one byte 0/1,
//! integers and bit strings little-endian two's complement of their size,
//! REAL and LREAL IEC 60559 single and double, TIME, DATE, TOD and DT (and
//! their long forms) as 8-byte counts (nanoseconds; DATE in seconds),
//! enumerations as their base integer, a STRING or WSTRING as a 2-byte
//! length then its capacity of 1- or 2-byte characters. The generated C
//! stores the same bytes (`stc_meta.h`).

use stc_syntax::token::ElemType;
use stc_values::Value;

/// Reads a scalar of an elementary type at `off`.
pub fn read_scalar(mem: &[u8], off: u32, e: ElemType) -> Option<Value> {
    use ElemType as E;
    let o = off as usize;
    let b = |n: usize| mem.get(o..o + n);
    Some(match e {
        E::Bool => Value::Bool(*mem.get(o)? != 0),
        E::Sint => Value::Int(i8::from_le_bytes(b(1)?.try_into().ok()?) as i128),
        E::Usint | E::Byte | E::Char => Value::Int(*mem.get(o)? as i128),
        E::Int => Value::Int(i16::from_le_bytes(b(2)?.try_into().ok()?) as i128),
        E::Uint | E::Word | E::Wchar => {
            Value::Int(u16::from_le_bytes(b(2)?.try_into().ok()?) as i128)
        }
        E::Dint => Value::Int(i32::from_le_bytes(b(4)?.try_into().ok()?) as i128),
        E::Udint | E::Dword => Value::Int(u32::from_le_bytes(b(4)?.try_into().ok()?) as i128),
        E::Ulint | E::Lword => Value::Int(u64::from_le_bytes(b(8)?.try_into().ok()?) as i128),
        E::Lint | E::Time | E::Ltime | E::Date | E::Ldate | E::Tod | E::Ltod | E::Dt | E::Ldt => {
            Value::Int(i64::from_le_bytes(b(8)?.try_into().ok()?) as i128)
        }
        E::Real => Value::Real(f32::from_le_bytes(b(4)?.try_into().ok()?) as f64),
        E::Lreal => Value::Real(f64::from_le_bytes(b(8)?.try_into().ok()?)),
        E::String | E::Wstring => return None,
    })
}

/// Writes a scalar of an elementary type at `off` (integers keep their low
/// bits; the caller has converted the value).
pub fn write_scalar(mem: &mut [u8], off: u32, e: ElemType, v: &Value) -> bool {
    use ElemType as E;
    let o = off as usize;
    let size = crate::layout::elem_size(e) as usize;
    let Some(dst) = mem.get_mut(o..o + size) else {
        return false;
    };
    match (e, v) {
        (E::Bool, Value::Bool(b)) => dst[0] = *b as u8,
        (E::Bool, Value::Int(i)) => dst[0] = (*i != 0) as u8,
        (E::Real, Value::Real(r)) => dst.copy_from_slice(&(*r as f32).to_le_bytes()),
        (E::Lreal, Value::Real(r)) => dst.copy_from_slice(&r.to_le_bytes()),
        (_, Value::Int(i)) => dst.copy_from_slice(&i.to_le_bytes()[..size]),
        (_, Value::Bool(b)) => {
            dst.fill(0);
            dst[0] = *b as u8;
        }
        _ => return false,
    }
    true
}

/// A STRING or WSTRING: a 2-byte length, then `cap` characters.
pub fn read_string(mem: &[u8], off: u32, wide: bool, cap: u32) -> Option<Value> {
    let o = off as usize;
    let len = (u16::from_le_bytes(mem.get(o..o + 2)?.try_into().ok()?) as u32).min(cap) as usize;
    if wide {
        let bytes = mem.get(o + 2..o + 2 + 2 * len)?;
        Some(Value::WStr(
            bytes
                .chunks_exact(2)
                .map(|c| u16::from_le_bytes([c[0], c[1]]))
                .collect(),
        ))
    } else {
        Some(Value::Str(mem.get(o + 2..o + 2 + len)?.to_vec()))
    }
}

/// Writes a STRING or WSTRING (truncated to its capacity `cap`).
pub fn write_string(mem: &mut [u8], off: u32, wide: bool, cap: u32, v: &Value) -> bool {
    let o = off as usize;
    match (wide, v) {
        (false, Value::Str(s)) => {
            let n = s.len().min(cap as usize);
            let Some(dst) = mem.get_mut(o..o + 2 + n) else {
                return false;
            };
            dst[..2].copy_from_slice(&(n as u16).to_le_bytes());
            dst[2..].copy_from_slice(&s[..n]);
            true
        }
        (true, Value::WStr(s)) => {
            let n = s.len().min(cap as usize);
            let Some(dst) = mem.get_mut(o..o + 2 + 2 * n) else {
                return false;
            };
            dst[..2].copy_from_slice(&(n as u16).to_le_bytes());
            for (i, u) in s[..n].iter().enumerate() {
                dst[2 + 2 * i..4 + 2 * i].copy_from_slice(&u.to_le_bytes());
            }
            true
        }
        _ => false,
    }
}
