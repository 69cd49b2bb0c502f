//! Phase timings of construction on a large torus: `cargo run --release --example prof_build`.
use std::time::Instant;
use topomesh::{primitives, BuildOptions, Mesh};

fn main() {
    let t = primitives::torus(1200, 800, 3.0, 1.0).unwrap();
    let p = t.to_polygons();
    let sizes: Vec<i64> = p.sizes.iter().map(|&s| s as i64).collect();
    let idx: Vec<i64> = p.indices.iter().map(|&s| s as i64).collect();
    for _ in 0..3 {
        let pos = t.positions().to_vec();
        let t0 = Instant::now();
        let m = Mesh::from_polygons(pos, &sizes, &idx, BuildOptions::default()).unwrap();
        let t1 = Instant::now();
        m.validate().unwrap();
        let t2 = Instant::now();
        let g = m.genus();
        let t3 = Instant::now();
        println!(
            "F={} build {:.1} ms, validate {:.1} ms, genus {:.1} ms (g={g})",
            m.n_faces(),
            (t1 - t0).as_secs_f64() * 1e3,
            (t2 - t1).as_secs_f64() * 1e3,
            (t3 - t2).as_secs_f64() * 1e3
        );
    }
}
