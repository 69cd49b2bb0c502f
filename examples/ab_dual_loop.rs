//! Dual Loop on the 100k-quad torus, the composition (dual, Loop, dual)
//! against the one-pass build, alternating in one process (issue 16):
//! `RAYON_NUM_THREADS=1 cargo run --release --example ab_dual_loop [N]`
//! prints the best and median of N calls each (ms, M output faces/s).
//! `TOPOMESH_HUGE_PAGES=1` advises blocks of 4–64 MiB to use huge pages, as
//! the Python extension's allocator then does (`src/python/alloc.rs`; off
//! by default there and here).
use std::alloc::{GlobalAlloc, Layout, System};
use std::time::Instant;
use topomesh::schemes::{dual::dual, loop_subdivision::loop_subdivision, topmod::compose};
use topomesh::{primitives, Mesh, Result};

struct Huge;
extern "C" {
    fn madvise(addr: *mut u8, len: usize, advice: i32) -> i32;
}
static HUGE_ON: std::sync::atomic::AtomicBool = std::sync::atomic::AtomicBool::new(false);

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

/// MADV_HUGEPAGE (14) on the 2 MiB-aligned interior of blocks of 4 to 64
/// MiB, the extension allocator's bounds (`src/python/alloc.rs`).
fn advise(p: *mut u8, size: usize) -> *mut u8 {
    const HP: usize = 2 << 20;
    if !p.is_null() && (4 << 20..=64 << 20).contains(&size) && HUGE_ON.load(std::sync::atomic::Ordering::Relaxed) {
        let (start, end) = ((p as usize).next_multiple_of(HP), (p as usize + size) & !(HP - 1));
        if end > start {
            // SAFETY: advice on a block just allocated; contents unchanged.
            unsafe { madvise(start as *mut u8, end - start, 14) };
        }
    }
    p
}

#[global_allocator]
static GLOBAL: Huge = Huge;

fn main() {
    if std::env::var("TOPOMESH_HUGE_PAGES").is_ok_and(|v| !matches!(v.trim(), "" | "0")) {
        HUGE_ON.store(true, std::sync::atomic::Ordering::Relaxed);
    }
    let reps: usize = std::env::args().nth(1).map_or(7, |s| s.parse().unwrap());
    let t = primitives::torus(400, 250, 3.0, 1.0).unwrap();
    type Op = fn(&Mesh) -> Result<Mesh>;
    let ops: [(&str, Op); 2] = [("composition", |m| dual(&loop_subdivision(&dual(m)?)?)), ("one pass", compose::dual_loop)];
    let (a, b) = (ops[0].1(&t).unwrap(), ops[1].1(&t).unwrap());
    assert!(a == b, "the builds differ");
    let faces = a.n_faces() as f64;
    drop((a, b));
    let mut times = vec![Vec::new(); ops.len()];
    // AB_ONLY=1: the one pass alone (for a profiler)
    let only = std::env::var("AB_ONLY").is_ok_and(|v| v == "1");
    for _ in 0..reps {
        for (i, (_, op)) in ops.iter().enumerate() {
            if only && i == 0 {
                times[0].push(0.0);
                continue;
            }
            let s = Instant::now();
            let r = op(&t).unwrap();
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
