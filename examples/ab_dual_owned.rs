//! Dual of a mesh given up (written over its columns) against the borrowed
//! dual, one thread (issue 19): `RAYON_NUM_THREADS=1 cargo run --release
//! --example ab_dual_owned [ROUNDS]`; the clone handed over is made before
//! the clock starts. Median ms per call on the 400×250 torus and the
//! 82k-triangle sphere.
use std::time::Instant;
use topomesh::schemes::{dual::{dual, dual_level_owned}, level::Request, loop_subdivision::loop_subdivision};
use topomesh::{primitives, Mesh};

fn main() {
    let rounds: usize = std::env::args().nth(1).and_then(|s| s.parse().ok()).unwrap_or(15);
    let mut sphere = primitives::icosahedron();
    for _ in 0..6 {
        sphere = loop_subdivision(&sphere).unwrap();
    }
    for (name, m) in [("torus", primitives::torus(400, 250, 3.0, 1.0).unwrap()), ("sphere", sphere)] {
        let (mut a, mut b) = (Vec::new(), Vec::new());
        for _ in 0..rounds {
            let c: Mesh = m.clone();
            let only = std::env::var("MODE").unwrap_or_default();
            let t = Instant::now();
            let x = if only == "owned" { Mesh::new() } else { dual(&m).unwrap() };
            a.push(t.elapsed().as_secs_f64() * 1e3);
            drop(x);
            let t = Instant::now();
            let y = if only == "borrowed" { c } else { dual_level_owned(c, &Request::plain()).unwrap().mesh };
            b.push(t.elapsed().as_secs_f64() * 1e3);
            drop(y);
        }
        let med = |v: &mut Vec<f64>| {
            v.sort_by(f64::total_cmp);
            v[v.len() / 2]
        };
        println!("{name}: borrowed {:.2} ms, owned {:.2} ms (median of {rounds})", med(&mut a), med(&mut b));
    }
}
