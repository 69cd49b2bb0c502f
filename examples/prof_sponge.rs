//! Time of `menger_sponge(level)` in the core (issue 19's sponge row, no
//! Python around it): `cargo run --release --example prof_sponge [CALLS]`,
//! median and best per level 0–5 (`LEVEL=k`: that one), and of the memory-budget
//! check alone.
use std::time::Instant;
use topomesh::schemes::menger_sponge::menger_sponge;

fn main() {
    let calls: usize = std::env::args().nth(1).and_then(|s| s.parse().ok()).unwrap_or(9);
    // LEVEL=k: that level only (for `perf`)
    let only: Option<u32> = std::env::var("LEVEL").ok().and_then(|s| s.parse().ok());
    for level in 0..=5u32 {
        if only.is_some_and(|k| k != level) {
            continue;
        }
        let mut t: Vec<f64> = (0..if level == 5 { 3 } else { calls })
            .map(|_| {
                let t0 = Instant::now();
                let m = menger_sponge(level).unwrap();
                let s = t0.elapsed().as_secs_f64();
                drop(m);
                s
            })
            .collect();
        t.sort_by(f64::total_cmp);
        println!("level {level}: median {:.3} ms, best {:.3} ms", t[t.len() / 2] * 1e3, t[0] * 1e3);
    }
    let t0 = Instant::now();
    for _ in 0..100 {
        topomesh::budget::check("x", "y", 1000).unwrap();
    }
    println!("budget::check: {:.1} us per call", t0.elapsed().as_secs_f64() * 1e4);
}
