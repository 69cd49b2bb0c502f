//! Time of the crossing report of the wireframe tools (issue 16) on tori of
//! growing size, one thread: `RAYON_NUM_THREADS=1 cargo run --release
//! --example prof_crossing [sizes...]` (a size n is the 2n×n quad torus).
use std::time::Instant;
use topomesh::{primitives, Mesh};

fn main() {
    let sizes: Vec<usize> = std::env::args().skip(1).map(|s| s.parse().unwrap()).collect();
    for n in if sizes.is_empty() { vec![50, 100, 200] } else { sizes } {
        let t = primitives::torus(2 * n, n, 3.0, 1.0).unwrap();
        let (p, v) = (t.positions(), t.halfedge_columns().1);
        let shortest = (0..t.n_edges()).map(|e| (p[v[2 * e] as usize] - p[v[2 * e + 1] as usize]).length()).fold(f64::INFINITY, f64::min);
        for (name, build) in [("wireframe", Box::new(|m: &Mesh| m.wireframe(0.1 * shortest, None)) as Box<dyn Fn(&Mesh) -> topomesh::Result<Mesh>>), ("columns", Box::new(|m: &Mesh| m.wireframe_columns(0.1 * shortest, 4)))] {
            let t0 = Instant::now();
            let out = build(&t).unwrap();
            let tb = t0.elapsed().as_secs_f64();
            let t1 = Instant::now();
            let k = topomesh::geometry::crossing::crossings_of_new_faces(&Mesh::new(), &out);
            let tc = t1.elapsed().as_secs_f64();
            println!("{name:10} torus {:>6} faces: build {:7.1} ms, crossings {:8.1} ms ({k} pairs), {} faces out, {:.2} M faces/s overall", t.n_faces(), tb * 1e3, tc * 1e3, out.n_faces(), out.n_faces() as f64 / (tb + tc) / 1e6);
        }
    }
}
