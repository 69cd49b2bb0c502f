//! Hashes of generalized Menger outputs (positions bit for bit, face
//! cycles) and of their reports (crossing pairs and vertices, rounds, face
//! factors), both constructions, with and without the thickness reduction: run it from two
//! builds and `diff` the outputs to check that a change leaves every
//! output as it was. `cargo run --release --example menger_hashes [big]`
//! (`big` adds the catalog's 400×250 torus, one iteration).
use std::hash::{Hash, Hasher};
use topomesh::{primitives, Mesh};
use topomesh::schemes::menger::{menger_reported, MengerOptions, Offset};

fn h(m: &Mesh) -> (u64, u64) {
    let mut a = std::collections::hash_map::DefaultHasher::new();
    for p in m.positions() { p.x.to_bits().hash(&mut a); p.y.to_bits().hash(&mut a); p.z.to_bits().hash(&mut a); }
    let mut b = std::collections::hash_map::DefaultHasher::new();
    for f in m.faces() { let v: Vec<u32> = m.face_vertices(f).map(|v| v.0).collect(); v.hash(&mut b); }
    (a.finish(), b.finish())
}

fn main() {
    let mut cases: Vec<(String, Mesh, usize)> = vec![
        ("cube".into(), primitives::cube(), 3), ("tetrahedron".into(), primitives::tetrahedron(), 4), ("octahedron".into(), primitives::octahedron(), 3),
        ("icosahedron".into(), primitives::icosahedron(), 3), ("dodecahedron".into(), primitives::dodecahedron(), 3),
        ("torus24".into(), primitives::torus(24, 12, 1.0, 0.4).unwrap(), 2), ("genus2".into(), primitives::genus_surface(2).unwrap(), 2),
    ];
    if std::env::args().any(|a| a == "big") { cases.push(("torus400".into(), primitives::torus(400, 250, 1.0, 0.4).unwrap(), 1)); }
    for (offset, no_reduce) in [(Offset::Merged, false), (Offset::Merged, true), (Offset::PerFace, false), (Offset::PerFace, true)] {
        let o = MengerOptions { reduce_thickness: !no_reduce, offset, ..Default::default() };
        for (name, m0, n) in &cases {
            if no_reduce && name == "torus400" { continue; }
            let mut m = m0.clone();
            for k in 1..=*n {
                let (x, r) = menger_reported(&m, &o).unwrap();
                let mut fh = std::collections::hash_map::DefaultHasher::new();
                for f in &r.face_factor { f.to_bits().hash(&mut fh); }
                println!("{offset:?} {name} {k} reduce={} faces {} hash {:x?} pairs {:?} vertices {} rounds {} factors {:x}", !no_reduce, x.n_faces(), h(&x), r.crossing_pairs, r.crossing_vertices, r.rounds, fh.finish());
                m = x;
            }
        }
    }
}
