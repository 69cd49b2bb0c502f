//! Truncate (`t = dkd`) on the 100k-quad torus, the composition (the
//! first dual, then the fused `dual(kis(·))`, as `conway "zd"` runs it)
//! against the one-pass build, alternating in one process (issue 16):
//! `RAYON_NUM_THREADS=1 cargo run --release --example ab_truncate [N]`
//! prints the best and median of N calls each (ms, M output faces/s) and
//! the FNV hash of both outputs (`prof_keyed`'s), with zip (`dk`, the
//! same output size) for reference. Large blocks are advised
//! huge pages as in `ab_dual_loop`; `TOPOMESH_HUGE_PAGES=0` turns that off.
use std::alloc::{GlobalAlloc, Layout, System};
use std::time::Instant;
use topomesh::schemes::conway::conway;
use topomesh::{primitives, Mesh, Result};

struct Huge;
extern "C" {
    fn madvise(addr: *mut u8, len: usize, advice: i32) -> i32;
}
static HUGE_ON: std::sync::atomic::AtomicBool = std::sync::atomic::AtomicBool::new(true);

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
/// MiB, the extension allocator's default bounds (`src/python/alloc.rs`).
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

fn hash(m: &Mesh) -> u64 {
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

fn main() {
    if std::env::var("TOPOMESH_HUGE_PAGES").is_ok_and(|v| v == "0") {
        HUGE_ON.store(false, std::sync::atomic::Ordering::Relaxed);
    }
    let reps: usize = std::env::args().nth(1).map_or(7, |s| s.parse().unwrap());
    let t = primitives::torus(400, 250, 3.0, 1.0).unwrap();
    type Op = fn(&Mesh) -> Result<Mesh>;
    // zip (`dk`, the same output size, already one pass) for reference
    let ops: [(&str, Op); 3] = [("composition", |m| conway("zd", Some(m))), ("one pass", |m| conway("t", Some(m))), ("zip", |m| conway("z", Some(m)))];
    let (a, b) = (ops[0].1(&t).unwrap(), ops[1].1(&t).unwrap());
    let (ha, hb) = (hash(&a), hash(&b));
    println!("hash composition {ha:016x}, one pass {hb:016x}");
    assert!(ha == hb && a == b, "the builds differ");
    let faces = a.n_faces() as f64;
    drop((a, b));
    let mut times = vec![Vec::new(); ops.len()];
    for _ in 0..reps {
        for (i, (_, op)) in ops.iter().enumerate() {
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
