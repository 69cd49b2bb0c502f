//! Populating a fresh output buffer's pages before its fill (issue 19).
//!
//! A scheme's output columns are new memory: glibc maps blocks above its
//! mmap threshold fresh and the fill then takes one page fault per 4 KiB
//! page, 2–4 µs each on the VMs measured, about 40 % of a midpoint or Loop
//! level on the 82k-triangle sphere. `madvise(MADV_POPULATE_WRITE)` (Linux
//! 5.14) maps a whole range in one call, without the per-page exception
//! entry, and is done here in parallel chunks of 4 MiB. Pages already mapped (heap
//! memory glibc reuses) are only walked. The contents are unchanged.
//!
//! Only for exactly-sized buffers the caller writes in full: populating
//! costs the memory a fill would have touched anyway, no more. Off with
//! `TOPOMESH_POPULATE=0` in the environment; elsewhere than Linux, or where
//! the kernel refuses the advice (older than 5.14), it does nothing.

use rayon::prelude::*;
use std::sync::atomic::{AtomicU8, Ordering};

/// Below this many bytes a buffer is left to the fill's faults (glibc
/// serves it from the heap, whose pages warm calls reuse).
const MIN_BYTES: usize = 1 << 20;
/// Bytes per `madvise` call: a few milliseconds of the kernel's work, so a
/// Ctrl-C (which the calls cannot see) waits for at most one chunk per
/// thread (`tests/test_safety.py`: a 16 M-quad level's 1.5 GB of columns
/// in chunks of a quarter of each column held the interrupt 0.5–0.9 s).
const CHUNK: usize = 4 << 20;
const PAGE: usize = 4096;

/// 0: not decided yet, 1: on, 2: off (environment or refused by the kernel).
static STATE: AtomicU8 = AtomicU8::new(0);

fn on() -> bool {
    match STATE.load(Ordering::Relaxed) {
        1 => true,
        2 => false,
        _ => {
            let off = std::env::var("TOPOMESH_POPULATE").is_ok_and(|v| matches!(v.trim().to_ascii_lowercase().as_str(), "0" | "false" | "no" | "off"));
            let on = cfg!(target_os = "linux") && !off;
            STATE.store(if on { 1 } else { 2 }, Ordering::Relaxed);
            on
        }
    }
}

/// Turns the population on or off for this process (the Python module
/// sets it from `TOPOMESH_POPULATE` at import, refusing values it cannot
/// read); off also where the kernel refused it.
pub fn set_populate(on: bool) {
    STATE.store(if on && cfg!(target_os = "linux") { 1 } else { 2 }, Ordering::Relaxed);
}

/// Whether buffers are populated (see [`set_populate`]).
pub fn populate_on() -> bool {
    on()
}

#[cfg(target_os = "linux")]
extern "C" {
    fn madvise(addr: *mut u8, len: usize, advice: i32) -> i32;
}

/// `MADV_POPULATE_WRITE` (Linux 5.14).
#[cfg(target_os = "linux")]
const MADV_POPULATE_WRITE: i32 = 23;

/// Maps the pages of the first `n` elements of `v`'s allocation (its length
/// or its spare capacity), in parallel, before the caller writes them all.
pub fn populate<T>(v: &mut Vec<T>, n: usize) {
    let bytes = n.min(v.capacity()) * std::mem::size_of::<T>();
    if bytes < MIN_BYTES || !on() {
        return;
    }
    let start = (v.as_mut_ptr() as usize).next_multiple_of(PAGE);
    let end = (v.as_mut_ptr() as usize + bytes) & !(PAGE - 1);
    if end <= start {
        return;
    }
    let len = end - start;
    let refused = (0..len.div_ceil(CHUNK)).into_par_iter().any(|i| {
        // cancelled: the rest is left to the fill, which stops too
        if crate::cancel::requested() {
            return false;
        }
        let a = start + i * CHUNK;
        advise(a, CHUNK.min(end - a))
    });
    if refused {
        STATE.store(2, Ordering::Relaxed);
    }
}

/// One call on `len` bytes from page-aligned `addr`; whether the kernel
/// refused the advice itself (not a transient failure such as lack of memory,
/// which the fill's own faults then meet as before).
#[cfg(target_os = "linux")]
fn advise(addr: usize, len: usize) -> bool {
    // SAFETY: a page-aligned range inside one live allocation of the
    // caller's; the advice maps its pages and leaves their contents as they
    // are (zero for pages not yet mapped).
    let r = unsafe { madvise(addr as *mut u8, len, MADV_POPULATE_WRITE) };
    r != 0 && std::io::Error::last_os_error().raw_os_error() == Some(22) // EINVAL: kernel without the advice
}

#[cfg(not(target_os = "linux"))]
fn advise(_addr: usize, _len: usize) -> bool {
    true
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Contents survive, on spare capacity and on written elements.
    #[test]
    fn contents_unchanged() {
        let mut v: Vec<u64> = (0..1u64 << 19).collect();
        v.reserve_exact(1 << 19);
        let cap = v.capacity();
        populate(&mut v, cap);
        assert!(v.iter().enumerate().all(|(i, &x)| x == i as u64));
        let mut w: Vec<u32> = Vec::with_capacity(3 << 20);
        populate(&mut w, 3 << 20);
        w.extend(0..3u32 << 20);
        assert_eq!(w[(3 << 20) - 1], (3 << 20) - 1);
    }
}
