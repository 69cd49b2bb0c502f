//! Time of the closest-edge multi-face handle on the two caps of a prism
//! `Pn` (issue 16: TopMod's sorted list of every pair of sides was
//! quadratic): `cargo run --release --example prof_closest_edge [n ...]`;
//! with `HULL=1` also the convex-hull handle of the same caps.
use std::time::Instant;
use topomesh::schemes::conway::seeds;

fn main() {
    let ns: Vec<usize> = std::env::args().skip(1).map(|a| a.parse().expect("side counts")).collect();
    let ns = if ns.is_empty() { vec![1_000, 4_000, 16_000, 100_000] } else { ns };
    for n in ns {
        for (kind, m) in [("prism", seeds::prism(n).unwrap()), ("antiprism", seeds::antiprism(n).unwrap())] {
            let caps: Vec<usize> = (0..m.n_faces()).filter(|&f| m.face_degree(topomesh::FaceId::new(f)) == n).collect();
            let t = Instant::now();
            let (out, k) = m.multi_face_handle_edges(&caps).unwrap();
            println!("{kind:9} {n:>7} sides: closest edge {:9.1} ms, {k} bridges, {} faces out", t.elapsed().as_secs_f64() * 1e3, out.n_faces());
            if std::env::var_os("HULL").is_some() {
                let t = Instant::now();
                let out = m.multi_face_handle(&caps, 0.5, 0.5).unwrap();
                println!("{kind:9} {n:>7} sides: convex hull  {:9.1} ms, {} faces out", t.elapsed().as_secs_f64() * 1e3, out.n_faces());
            }
        }
    }
}
