//! Coverage-guided fuzzing of the bytecode loader, verifier and interpreter:
//! any bytes given to `stc_vm::format::decode` are rejected with an error or
//! accepted, and an accepted image runs every program without panicking
//! (faults are fine). Each input is tried as it is and resealed (correct
//! length and checksum), so mutations reach the tables and the verifier.
//!
//! Run: `cargo fuzz run load fuzz/seeds-stbc -- -max_total_time=600` (from
//! the repo root; the seeds are compiled conformance programs).

#![no_main]

use std::sync::Arc;

use libfuzzer_sys::fuzz_target;

fn try_load(bytes: &[u8]) {
    let Ok(img) = stc_vm::format::decode(bytes) else {
        return;
    };
    let img = Arc::new(img);
    let mut m = stc_vm::Machine::new(img.clone());
    let mut programs = img.programs.clone();
    for c in &img.configs {
        for r in &c.resources {
            programs.extend(r.programs.iter().cloned());
        }
    }
    for (k, p) in programs.iter().enumerate() {
        let _ = m.run_program(p, k as i64 * 1_000_000, 20_000);
    }
}

fuzz_target!(|data: &[u8]| {
    try_load(data);
    if data.len() >= 16 {
        let mut b = data.to_vec();
        let len = (b.len() - 16) as u32;
        b[8..12].copy_from_slice(&len.to_le_bytes());
        let crc = crc32fast::hash(&b[16..]);
        b[12..16].copy_from_slice(&crc.to_le_bytes());
        try_load(&b);
    }
});
