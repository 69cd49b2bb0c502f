//! Time of the wireframe tools alone (no crossing report) on the catalog's
//! 400×250 torus, one call after a warm-up, best and median of 7 (issue 16):
//! `RAYON_NUM_THREADS=1 cargo run --release --example prof_tools`.
use std::time::Instant;
use topomesh::{primitives, Mesh};

fn main() {
    let m = primitives::torus(400, 250, 3.0, 1.0).unwrap();
    let (p, v) = (m.positions(), m.halfedge_columns().1);
    let shortest = (0..m.n_edges()).map(|e| (p[v[2 * e] as usize] - p[v[2 * e + 1] as usize]).length()).fold(f64::INFINITY, f64::min);
    let t = 0.1 * shortest;
    let tools: [(&str, Box<dyn Fn(&Mesh) -> topomesh::Result<Mesh>>); 2] =
        [("wireframe", Box::new(move |m: &Mesh| m.wireframe(t, None))), ("columns", Box::new(move |m: &Mesh| m.wireframe_columns(t, 4)))];
    for (name, f) in &tools {
        let mut ts = Vec::new();
        let mut faces = 0;
        for _ in 0..8 {
            let t0 = Instant::now();
            let out = f(&m).unwrap();
            ts.push(t0.elapsed().as_secs_f64() * 1e3);
            faces = out.n_faces();
            drop(out);
        }
        ts.remove(0);
        ts.sort_by(f64::total_cmp);
        println!("{name:10} {faces} faces: best {:.1} ms, median {:.1} ms, {:.2} M faces/s at the median", ts[0], ts[3], faces as f64 / ts[3] / 1e3);
    }
}
