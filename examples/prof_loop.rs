//! Loop subdivision timing on an 81,920-triangle icosphere (the benchmark's
//! input), best of N: `cargo run --release --example prof_loop [N]`.
use std::time::Instant;
use topomesh::{primitives, schemes::loop_subdivision::loop_subdivision};

fn main() {
    let reps: usize = std::env::args().nth(1).map_or(20, |s| s.parse().unwrap());
    let mut m = primitives::icosahedron();
    for _ in 0..6 {
        m = loop_subdivision(&m).unwrap();
    }
    let mut best = f64::INFINITY;
    let mut nf = 0;
    for _ in 0..reps {
        let t0 = Instant::now();
        let r = loop_subdivision(&m).unwrap();
        best = best.min(t0.elapsed().as_secs_f64() * 1e3);
        nf = r.n_faces();
    }
    println!("loop: F {} -> {nf}, best of {reps}: {best:.2} ms ({:.1} M faces/s)", m.n_faces(), nf as f64 / best / 1e3);
}
