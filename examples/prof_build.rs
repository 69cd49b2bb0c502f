//! Phase timings of construction, best of N:
//! `cargo run --release --example prof_build [MESH.bin] [N]`.
//!
//! Without a file: a 960k-quad torus. With one: a triangle mesh as raw
//! little-endian `[V: i64, F: i64, V×3 f64, F×3 i64]` (e.g. a trimesh
//! icosphere dumped with numpy's `tobytes`).
use std::time::Instant;
use glam::DVec3;
use topomesh::{primitives, BuildOptions, Mesh};

fn ms(a: Instant, b: Instant) -> f64 {
    (b - a).as_secs_f64() * 1e3
}

fn load(path: &str) -> (Vec<DVec3>, Vec<i64>, Vec<i64>) {
    let b = std::fs::read(path).expect("read mesh");
    let word = |i: usize| <[u8; 8]>::try_from(&b[8 * i..8 * i + 8]).unwrap();
    let (nv, nf) = (i64::from_le_bytes(word(0)) as usize, i64::from_le_bytes(word(1)) as usize);
    let pos = (0..nv)
        .map(|v| DVec3::from_array(std::array::from_fn(|k| f64::from_le_bytes(word(2 + 3 * v + k)))))
        .collect();
    let idx = (0..3 * nf).map(|i| i64::from_le_bytes(word(2 + 3 * nv + i))).collect();
    (pos, vec![3; nf], idx)
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let (pos, sizes, idx) = match args.get(1) {
        Some(p) => load(p),
        None => {
            let t = primitives::torus(1200, 800, 3.0, 1.0).unwrap();
            let p = t.to_polygons();
            (t.positions().to_vec(), p.sizes.iter().map(|&s| s as i64).collect(), p.indices.iter().map(|&s| s as i64).collect())
        }
    };
    let reps: usize = args.get(2).map_or(5, |s| s.parse().unwrap());
    // corner twins of the input, for the scheme builder
    let m0 = Mesh::from_polygons(pos.clone(), &sizes, &idx, BuildOptions::default()).unwrap();
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
    let sizes_u: Vec<u32> = sizes.iter().map(|&s| s as u32).collect();
    let verts: Vec<u32> = idx.iter().map(|&s| s as u32).collect();
    let twins_i64: Vec<i64> = twins.iter().map(|&t| t as i64).collect();
    let (idx_i32, twins_i32): (Vec<i32>, Vec<i32>) = (idx.iter().map(|&i| i as i32).collect(), twins.iter().map(|&t| t as i32).collect());
    let mut best = [f64::INFINITY; 6];
    let mut g = 0;
    for _ in 0..reps {
        let p0 = pos.clone();
        let t0 = Instant::now();
        let m = Mesh::from_polygons(p0, &sizes, &idx, BuildOptions::default()).unwrap();
        let t1 = Instant::now();
        m.validate().unwrap();
        let t2 = Instant::now();
        g = m.genus();
        let t3 = Instant::now();
        let m2 = Mesh::from_corner_twins(pos.clone(), &sizes_u, &verts, &twins).unwrap();
        let t4 = Instant::now();
        assert_eq!(m2.n_edges(), m.n_edges());
        let p1 = pos.clone();
        let t5 = Instant::now();
        let m3 = Mesh::from_corner_twins_i64(p1, &sizes, &idx, &twins_i64).unwrap();
        let t6 = Instant::now();
        assert_eq!(m3.n_edges(), m.n_edges());
        drop(m3);
        let p2 = pos.clone();
        let t7 = Instant::now();
        let m4 = Mesh::from_corner_twins_i32(p2, &sizes, &idx_i32, &twins_i32).unwrap();
        let t8 = Instant::now();
        assert_eq!(m4.n_edges(), m.n_edges());
        for (b, t) in best.iter_mut().zip([ms(t0, t1), ms(t1, t2), ms(t2, t3), ms(t3, t4), ms(t5, t6), ms(t7, t8)]) {
            *b = b.min(t);
        }
    }
    println!(
        "F={} best of {reps}: from_polygons {:.1} ms, validate {:.1} ms, genus {:.1} ms (g={g}), from_corner_twins {:.1} ms, from_corner_twins_i64 {:.1} ms, from_corner_twins_i32 {:.1} ms",
        m0.n_faces(),
        best[0],
        best[1],
        best[2],
        best[3],
        best[4],
        best[5]
    );
}
