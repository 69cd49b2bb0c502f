//! Time of one generalized Menger iteration on a quad torus, one thread (the
//! catalog row, issue 16): `RAYON_NUM_THREADS=1 cargo run --release
//! --example prof_menger [MAJOR MINOR [CALLS]]` (default the 400×250 torus,
//! 3 calls; the first pays for fresh memory, compare the later ones).
//! `NOREDUCE=1`: without the thickness reduction (the construction alone).
use std::time::Instant;
use topomesh::primitives;
use topomesh::schemes::menger::{menger_reported, MengerOptions};

/// CPU seconds of this process so far (user + system, every thread), from
/// /proc: steadier than the wall clock on a shared machine.
fn cpu_secs() -> f64 {
    let s = std::fs::read_to_string("/proc/self/stat").unwrap_or_default();
    let f: Vec<&str> = s.rsplit_once(')').map_or("", |x| x.1).split_whitespace().collect();
    let tick = |i: usize| f.get(i).and_then(|x| x.parse::<f64>().ok()).unwrap_or(0.0);
    (tick(11) + tick(12)) / 100.0
}

fn main() {
    let a: Vec<usize> = std::env::args().skip(1).map(|s| s.parse().unwrap()).collect();
    let (major, minor, calls) = (a.first().copied().unwrap_or(400), a.get(1).copied().unwrap_or(250), a.get(2).copied().unwrap_or(3));
    let t = primitives::torus(major, minor, 1.0, 0.4).unwrap();
    for _ in 0..calls {
        let (t0, c0) = (Instant::now(), cpu_secs());
        let o = MengerOptions { reduce_thickness: std::env::var("NOREDUCE").is_err(), ..Default::default() };
        let (out, r) = menger_reported(&t, &o).unwrap();
        let (s, c) = (t0.elapsed().as_secs_f64(), cpu_secs() - c0);
        println!("torus {major}x{minor}: {} faces out in {:.1} ms ({:.2} M faces/s; CPU {:.0} ms), pairs {:?}, rounds {}", out.n_faces(), s * 1e3, out.n_faces() as f64 / s / 1e6, c * 1e3, r.crossing_pairs, r.rounds);
    }
}
