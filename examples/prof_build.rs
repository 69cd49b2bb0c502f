//! Phase timings of construction on a large torus: `cargo run --release --example prof_build`.
use std::time::Instant;
use topomesh::{primitives, BuildOptions, Mesh};

fn ms(a: Instant, b: Instant) -> f64 {
    (b - a).as_secs_f64() * 1e3
}

fn main() {
    let t = primitives::torus(1200, 800, 3.0, 1.0).unwrap();
    let p = t.to_polygons();
    let sizes: Vec<i64> = p.sizes.iter().map(|&s| s as i64).collect();
    let idx: Vec<i64> = p.indices.iter().map(|&s| s as i64).collect();
    // corner twins of the quad grid, for the scheme builder
    let m0 = Mesh::from_polygons(t.positions().to_vec(), &sizes, &idx, BuildOptions::default()).unwrap();
    let mut corner_of_he = vec![0u32; m0.n_halfedges()];
    let mut k = 0u32;
    for f in m0.faces() {
        for h in m0.face_halfedges(f) {
            corner_of_he[h.idx()] = k;
            k += 1;
        }
    }
    let mut twins = vec![0u32; k as usize];
    for h in m0.halfedges() {
        twins[corner_of_he[h.idx()] as usize] = corner_of_he[h.twin().idx()];
    }
    let verts: Vec<u32> = p.indices.clone();
    for _ in 0..3 {
        let pos = t.positions().to_vec();
        let t0 = Instant::now();
        let m = Mesh::from_polygons(pos, &sizes, &idx, BuildOptions::default()).unwrap();
        let t1 = Instant::now();
        m.validate().unwrap();
        let t2 = Instant::now();
        let g = m.genus();
        let t3 = Instant::now();
        let m2 = Mesh::from_corner_twins(t.positions().to_vec(), &p.sizes, &verts, &twins).unwrap();
        let t4 = Instant::now();
        assert_eq!(m2.n_edges(), m.n_edges());
        println!(
            "F={} from_polygons {:.1} ms, validate {:.1} ms, genus {:.1} ms (g={g}), from_corner_twins {:.1} ms",
            m.n_faces(),
            ms(t0, t1),
            ms(t1, t2),
            ms(t2, t3),
            ms(t3, t4)
        );
    }
}
