//! Time of the crossing check after a local change (issue 16: the
//! multi-face handle rows), one thread: `RAYON_NUM_THREADS=1 cargo run
//! --release --example prof_local_check`. Splits the tool, the whole call of
//! `crossings_of_new_faces`, and a whole triangulation of the output
//! (which the check did before it became local).
use std::time::Instant;
use topomesh::primitives;

fn best<T>(n: usize, mut f: impl FnMut() -> T) -> (f64, T) {
    let mut b = f64::INFINITY;
    let mut out = f();
    for _ in 0..n {
        let t = Instant::now();
        out = f();
        b = b.min(t.elapsed().as_secs_f64() * 1e3);
    }
    (b, out)
}

fn main() {
    let m = primitives::torus(400, 250, 3.0, 1.0).unwrap();
    let faces = [62usize, 187];
    for (name, hull) in [("closest edge", false), ("convex hull", true)] {
        let (tt, out) = best(10, || if hull { m.multi_face_handle(&faces, 0.5, -0.25).unwrap() } else { m.multi_face_handle_edges(&faces).unwrap().0 });
        let (tc, k) = best(10, || topomesh::geometry::crossing::crossings_of_new_faces(&m, &out));
        let (tr, _) = best(10, || out.triangulate());
        println!("{name:12}: tool {tt:6.2} ms, check {tc:6.2} ms ({k} pairs; a whole triangulation would take {tr:6.2} ms), {} faces out", out.n_faces());
    }
}
