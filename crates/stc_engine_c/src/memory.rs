//! The C program's objects as one `u32` address space.
//!
//! Every object the model names (a global, a program instance, a process
//! image slot, a constant a configuration connects) is a region: its host
//! address, its size, and a base in the model's address space. Objects that
//! overlap in the host (a located global is its slot) are merged into one
//! region. A model address is valid only inside one region; a reference
//! slot holds a host pointer, which is translated back to a model address
//! when it points into a region.

use std::ffi::c_void;

/// One object, or several that overlap.
#[derive(Clone, Copy, Debug)]
struct Region {
    host: usize,
    len: usize,
    base: u32,
    writable: bool,
}

/// The regions of a program, sorted by host address and by base.
pub(crate) struct Regions {
    regions: Vec<Region>,
}

/// Alignment of every region's base (the strictest of any C object).
const ALIGN: u64 = 16;

/// Collects regions before they are given bases.
#[derive(Default)]
pub(crate) struct RegionBuilder {
    objects: Vec<(usize, usize, bool)>,
}

impl RegionBuilder {
    /// An object at `ptr` of `len` bytes (`writable`: not a constant).
    pub(crate) fn add(&mut self, ptr: *const c_void, len: usize, writable: bool) {
        if !ptr.is_null() {
            self.objects.push((ptr as usize, len.max(1), writable));
        }
    }

    /// Merges overlapping objects and gives each region a base; `None`
    /// when they do not fit in the `u32` address space.
    pub(crate) fn finish(mut self) -> Option<Regions> {
        self.objects.sort();
        let mut regions: Vec<Region> = Vec::new();
        for (host, len, writable) in self.objects {
            if let Some(last) = regions.last_mut() {
                if host < last.host + last.len {
                    let end = (host + len).max(last.host + last.len);
                    last.len = end - last.host;
                    last.writable &= writable;
                    continue;
                }
            }
            regions.push(Region {
                host,
                len,
                base: 0,
                writable,
            });
        }
        // Base 0 stays unused: no object is at the model's address 0.
        let mut next: u64 = ALIGN;
        for r in &mut regions {
            r.base = u32::try_from(next).ok()?;
            next = (next + r.len as u64).div_ceil(ALIGN) * ALIGN;
        }
        u32::try_from(next).ok()?;
        Some(Regions { regions })
    }
}

impl Regions {
    /// The model address of a host pointer into a region.
    pub(crate) fn model_addr(&self, ptr: usize) -> Option<u32> {
        let i = self
            .regions
            .partition_point(|r| r.host <= ptr)
            .checked_sub(1)?;
        let r = &self.regions[i];
        let off = ptr - r.host;
        (off < r.len).then(|| r.base + off as u32)
    }

    /// The region holding `len` bytes at model address `addr`, and the
    /// offset of `addr` in it.
    fn find(&self, addr: u32, len: u32) -> Option<(&Region, usize)> {
        let i = self
            .regions
            .partition_point(|r| r.base <= addr)
            .checked_sub(1)?;
        let r = &self.regions[i];
        let off = (addr - r.base) as usize;
        (off.checked_add(len as usize)? <= r.len).then_some((r, off))
    }

    pub(crate) fn bytes(&self, addr: u32, len: u32) -> Option<&[u8]> {
        let (r, off) = self.find(addr, len)?;
        // SAFETY: the region is an object of the loaded library (its size
        // from the library's own tables), alive while the engine holds the
        // library; no C code runs while the engine is borrowed.
        Some(unsafe { std::slice::from_raw_parts((r.host + off) as *const u8, len as usize) })
    }

    pub(crate) fn bytes_mut(&mut self, addr: u32, len: u32) -> Option<&mut [u8]> {
        let (r, off) = self.find(addr, len)?;
        if !r.writable {
            return None;
        }
        // SAFETY: as in `bytes`; the region is a variable (not in read-only
        // memory) and the engine is borrowed mutably, so this is the only
        // reference to it.
        Some(unsafe { std::slice::from_raw_parts_mut((r.host + off) as *mut u8, len as usize) })
    }

    /// The model address a reference slot (a C pointer) points to.
    pub(crate) fn deref(&self, slot: u32) -> Option<u32> {
        const P: usize = std::mem::size_of::<usize>();
        let b = self.bytes(slot, P as u32)?;
        let mut raw = [0u8; P];
        raw.copy_from_slice(b);
        self.model_addr(usize::from_ne_bytes(raw))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn overlapping_objects_are_one_region_and_addresses_translate_both_ways() {
        let a = [0u8; 40];
        let b = [7u8; 8];
        let mut rb = RegionBuilder::default();
        rb.add(a.as_ptr().cast(), 40, true);
        rb.add(a[8..].as_ptr().cast(), 4, true);
        rb.add(b.as_ptr().cast(), 8, false);
        rb.add(std::ptr::null(), 8, true);
        let r = rb.finish().unwrap();
        assert_eq!(r.regions.len(), 2);
        let base_a = r.model_addr(a.as_ptr() as usize).unwrap();
        assert_eq!(r.model_addr(a[8..].as_ptr() as usize), Some(base_a + 8));
        assert_eq!(r.bytes(base_a + 36, 4).map(<[u8]>::len), Some(4));
        assert!(r.bytes(base_a + 37, 4).is_none());
        assert!(r.bytes(0, 1).is_none());
        let base_b = r.model_addr(b.as_ptr() as usize).unwrap();
        assert_eq!(r.bytes(base_b, 8), Some(&[7u8; 8][..]));
        assert_ne!(base_a, base_b);
        assert_eq!(r.model_addr(1), None);
    }
}
