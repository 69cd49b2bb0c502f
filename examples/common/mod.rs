//! What the A/B and profiling examples share: the extension allocator's
//! opt-in huge-page advice, an FNV hash of a mesh to compare builds, and the
//! alternating timing loop.
#![allow(dead_code)] // each example uses part of it

use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Instant;
use topomesh::Mesh;

/// The system allocator with `MADV_HUGEPAGE` on the 2 MiB-aligned interior
/// of blocks of 4 to 64 MiB when [`huge_pages_from_env`] turned it on, as the
/// Python extension's allocator does with `TOPOMESH_HUGE_PAGES=1`
/// (`src/python/alloc.rs`; off by default there and here). An example opts
/// in with `#[global_allocator] static GLOBAL: common::Huge = common::Huge;`.
pub struct Huge;
static HUGE_ON: AtomicBool = AtomicBool::new(false);
extern "C" {
    fn madvise(addr: *mut u8, len: usize, advice: i32) -> i32;
}

unsafe impl GlobalAlloc for Huge {
    unsafe fn alloc(&self, l: Layout) -> *mut u8 {
        advise(unsafe { System.alloc(l) }, l.size())
    }
    unsafe fn alloc_zeroed(&self, l: Layout) -> *mut u8 {
        advise(unsafe { System.alloc_zeroed(l) }, l.size())
    }
    unsafe fn dealloc(&self, p: *mut u8, l: Layout) {
        unsafe { System.dealloc(p, l) }
    }
}

fn advise(p: *mut u8, size: usize) -> *mut u8 {
    const HP: usize = 2 << 20;
    if !p.is_null() && (4 << 20..=64 << 20).contains(&size) && HUGE_ON.load(Ordering::Relaxed) {
        let (start, end) = ((p as usize).next_multiple_of(HP), (p as usize + size) & !(HP - 1));
        if end > start {
            // SAFETY: advice on a block just allocated; contents unchanged.
            unsafe { madvise(start as *mut u8, end - start, 14) };
        }
    }
    p
}

/// Reads `TOPOMESH_HUGE_PAGES` as the extension does (`src/python/perf.rs`:
/// 1/true/yes/on turn the advice on, 0/false/no/off or empty leave it off,
/// anything else is refused).
pub fn huge_pages_from_env() {
    if let Ok(v) = std::env::var("TOPOMESH_HUGE_PAGES") {
        let on = match v.trim().to_ascii_lowercase().as_str() {
            "1" | "true" | "yes" | "on" => true,
            "" | "0" | "false" | "no" | "off" => false,
            _ => panic!("TOPOMESH_HUGE_PAGES = {v:?} must be 1 (advise huge pages) or 0 (the default)"),
        };
        HUGE_ON.store(on, Ordering::Relaxed);
    }
}

/// The A/B examples' start: the huge-page setting read, the repetitions
/// from the first argument (default 7) and the catalog's 400×250 torus.
pub fn setup() -> (usize, Mesh) {
    huge_pages_from_env();
    let reps: usize = std::env::args().nth(1).map_or(7, |s| s.parse().unwrap());
    (reps, topomesh::primitives::torus(400, 250, 3.0, 1.0).unwrap())
}

/// FNV-1a over the positions' bits, the face cycles and the corner twins.
pub fn hash(m: &Mesh) -> u64 {
    let mut h = 0xcbf29ce484222325u64;
    let mut eat = |x: u64| {
        for b in x.to_le_bytes() {
            h = (h ^ b as u64).wrapping_mul(0x100000001b3);
        }
    };
    for p in m.positions() {
        eat(p.x.to_bits());
        eat(p.y.to_bits());
        eat(p.z.to_bits());
    }
    let p = m.to_polygons();
    p.sizes.iter().for_each(|&s| eat(s as u64));
    p.indices.iter().for_each(|&s| eat(s as u64));
    m.corner_twins().iter().for_each(|&s| eat(s as u64));
    h
}

pub type Op = fn(&Mesh) -> topomesh::Result<Mesh>;

/// Runs the builds in turn `reps` times on `input` (skipping build `skip`
/// if given, for a profiler) and prints each one's best and median time
/// and output faces per second.
pub fn alternate(ops: &[(&str, Op)], input: &Mesh, reps: usize, skip: Option<usize>) {
    let faces = ops[0].1(input).unwrap().n_faces() as f64;
    let mut times = vec![Vec::new(); ops.len()];
    for _ in 0..reps {
        for (i, (_, op)) in ops.iter().enumerate() {
            if skip == Some(i) {
                times[i].push(0.0);
                continue;
            }
            let s = Instant::now();
            let r = op(input).unwrap();
            times[i].push(s.elapsed().as_secs_f64() * 1e3);
            drop(r);
        }
    }
    for ((name, _), ts) in ops.iter().zip(&mut times) {
        ts.sort_by(f64::total_cmp);
        let (best, med) = (ts[0], ts[ts.len() / 2]);
        println!("{name:12} best {best:7.2} ms  median {med:7.2} ms  ({:.2} / {:.2} M faces/s, {faces} faces)", faces / best / 1e3, faces / med / 1e3);
    }
}
