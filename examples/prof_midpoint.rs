//! Midpoint subdivision timing on the benchmark's 81,920-triangle icosphere
//! (dumped by `bench_subdivision.make_input("sphere")` to
//! `/tmp/sphere_v.bin` (float64) and `/tmp/sphere_f.bin` (int64)), best of N:
//! `cargo run --release --example prof_midpoint [N]`.
use std::time::Instant;
use topomesh::{schemes::midpoint::midpoint, BuildOptions, Mesh};

fn read(path: &str) -> Vec<u8> {
    std::fs::read(path).unwrap_or_else(|e| panic!("{path}: {e} (see the module docs)"))
}

fn main() {
    let reps: usize = std::env::args().nth(1).map_or(20, |s| s.parse().unwrap());
    let v: Vec<f64> = read("/tmp/sphere_v.bin").chunks_exact(8).map(|b| f64::from_le_bytes(b.try_into().unwrap())).collect();
    let f: Vec<i64> = read("/tmp/sphere_f.bin").chunks_exact(8).map(|b| i64::from_le_bytes(b.try_into().unwrap())).collect();
    let pos = v.chunks_exact(3).map(|p| glam::DVec3::new(p[0], p[1], p[2])).collect();
    let sizes = vec![3i64; f.len() / 3];
    let m = Mesh::from_polygons(pos, &sizes, &f, BuildOptions::default()).unwrap();
    let mut best = f64::INFINITY;
    let mut nf = 0;
    for _ in 0..reps {
        let t0 = Instant::now();
        let r = midpoint(&m).unwrap();
        best = best.min(t0.elapsed().as_secs_f64() * 1e3);
        nf = r.n_faces();
    }
    println!("midpoint: F {} -> {nf}, best of {reps}: {best:.2} ms ({:.1} M faces/s)", m.n_faces(), nf as f64 / best / 1e3);
}
